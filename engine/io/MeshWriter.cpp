#include "strata/io/MeshWriter.h"
#include "strata/io/ExportFormats.h"

#include <Model/COM/NMR_DLLInterfaces.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "strata/core/Error.h"

namespace strata::io {
namespace {

using Bytes = std::vector<unsigned char>;

void put(Bytes& out, const std::string& text) { out.insert(out.end(), text.begin(), text.end()); }

template <class T>
void putLittle(Bytes& out, T value) {
    static_assert(std::endian::native == std::endian::little, "STL is little-endian; so is every target strata builds for");
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    out.insert(out.end(), raw, raw + sizeof(T));
}

// A double that reads back to the same double, in the fewest digits that do
// (std::to_chars: several times faster than printf's %.17g, which mattered
// for exports of millions of vertices).
std::string exact(double x) {
    char text[32];
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, x);
    return std::string(text, r.ptr);
}

Bytes stl(const mesh::Mesh& mesh) {
    Bytes out;
    out.reserve(84 + mesh.triangles.size() * 50);
    std::string header = "binary STL written by strata";
    header.resize(80, ' ');
    put(out, header);
    putLittle<std::uint32_t>(out, static_cast<std::uint32_t>(mesh.triangles.size()));
    for (const auto& t : mesh.triangles) {
        const glm::dvec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        glm::dvec3 n = glm::cross(b - a, c - a);
        const double length = glm::length(n);
        n = length > 0.0 ? n / length : glm::dvec3(0.0);
        for (const glm::dvec3& v : {n, a, b, c}) {
            putLittle(out, static_cast<float>(v.x));
            putLittle(out, static_cast<float>(v.y));
            putLittle(out, static_cast<float>(v.z));
        }
        putLittle<std::uint16_t>(out, 0);
    }
    return out;
}

Bytes off(const mesh::Mesh& mesh) {
    Bytes out;
    put(out, "OFF\n" + std::to_string(mesh.positions.size()) + " " + std::to_string(mesh.triangles.size()) + " 0\n");
    for (const glm::dvec3& p : mesh.positions) put(out, exact(p.x) + " " + exact(p.y) + " " + exact(p.z) + "\n");
    for (const auto& t : mesh.triangles)
        put(out, "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n");
    return out;
}

Bytes obj(const mesh::Mesh& mesh) {
    Bytes out;
    put(out, "# written by strata\n");
    for (const glm::dvec3& p : mesh.positions) put(out, "v " + exact(p.x) + " " + exact(p.y) + " " + exact(p.z) + "\n");
    for (const auto& t : mesh.triangles)
        put(out, "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n");
    return out;
}

// lib3mf's objects, released however the writing ends.
class Lib3mf {
public:
    ~Lib3mf() {
        for (auto it = owned_.rbegin(); it != owned_.rend(); ++it) NMR::lib3mf_release(*it);
    }
    template <class T>
    T* keep(T* object) {
        if (object != nullptr) owned_.push_back(object);
        return object;
    }
    // Throws naming `what`, with lib3mf's own message from `object` when it has one.
    static void check(LIB3MFRESULT result, const char* what, NMR::PLib3MFBase* object = nullptr) {
        if (result == LIB3MF_OK) return;
        std::string message = std::string("lib3mf: ") + what + " failed";
        DWORD code = 0;
        LPCSTR detail = nullptr;
        if (object != nullptr && NMR::lib3mf_getlasterror(object, &code, &detail) == LIB3MF_OK && detail != nullptr) {
            message += std::string(": ") + detail;
        }
        throw Error(message);
    }

private:
    std::vector<NMR::PLib3MFBase*> owned_;
};

unsigned char channel(float v) { return static_cast<unsigned char>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); }

Bytes threeMf(const mesh::Mesh& mesh, std::span<const glm::vec4> colors) {
    Lib3mf lib;
    NMR::PLib3MFModel* model = nullptr;
    Lib3mf::check(NMR::lib3mf_createmodel(&model), "creating a model");
    lib.keep(model);
    NMR::PLib3MFModelMeshObject* object = nullptr;
    Lib3mf::check(NMR::lib3mf_model_addmeshobject(model, &object), "adding a mesh");
    lib.keep(object);
    Lib3mf::check(NMR::lib3mf_object_setnameutf8(object, "strata result"), "naming the mesh");
    std::vector<NMR::MODELMESHVERTEX> vertices(mesh.positions.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        vertices[i].m_fPosition[0] = static_cast<float>(mesh.positions[i].x);
        vertices[i].m_fPosition[1] = static_cast<float>(mesh.positions[i].y);
        vertices[i].m_fPosition[2] = static_cast<float>(mesh.positions[i].z);
    }
    std::vector<NMR::MODELMESHTRIANGLE> triangles(mesh.triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) triangles[i].m_nIndices[k] = mesh.triangles[i][static_cast<std::size_t>(k)];
    Lib3mf::check(NMR::lib3mf_meshobject_setgeometry(object, vertices.data(), static_cast<DWORD>(vertices.size()),
                                                     triangles.data(), static_cast<DWORD>(triangles.size())),
                  "setting the geometry");
    if (!colors.empty() && colors.size() == mesh.triangles.size()) {
        // One base material per distinct colour (3MF's base materials are opaque RGB).
        NMR::PLib3MFModelBaseMaterial* group = nullptr;
        Lib3mf::check(NMR::lib3mf_model_addbasematerialgroup(model, &group), "adding materials");
        lib.keep(group);
        DWORD groupId = 0;
        Lib3mf::check(NMR::lib3mf_resource_getresourceid(group, &groupId), "reading the materials' id");
        NMR::PLib3MFPropertyHandler* properties = nullptr;
        Lib3mf::check(NMR::lib3mf_meshobject_createpropertyhandler(object, &properties), "adding properties");
        lib.keep(properties);
        std::map<std::array<unsigned char, 3>, DWORD> materialOf;
        for (std::size_t i = 0; i < colors.size(); ++i) {
            const std::array<unsigned char, 3> rgb{channel(colors[i].r), channel(colors[i].g), channel(colors[i].b)};
            auto it = materialOf.find(rgb);
            if (it == materialOf.end()) {
                DWORD index = 0;
                char name[16];
                std::snprintf(name, sizeof name, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
                Lib3mf::check(NMR::lib3mf_basematerial_addmaterialutf8(group, name, rgb[0], rgb[1], rgb[2], &index),
                              "adding a material");
                it = materialOf.emplace(rgb, index).first;
            }
            Lib3mf::check(NMR::lib3mf_propertyhandler_setbasematerial(properties, static_cast<DWORD>(i), groupId, it->second),
                          "colouring a triangle");
        }
        // 3MF asks for an object-wide default beside the per-triangle ones: the first triangle's.
        NMR::PLib3MFDefaultPropertyHandler* defaults = nullptr;
        Lib3mf::check(NMR::lib3mf_object_createdefaultpropertyhandler(object, &defaults), "adding a default property");
        lib.keep(defaults);
        const std::array<unsigned char, 3> first{channel(colors[0].r), channel(colors[0].g), channel(colors[0].b)};
        Lib3mf::check(NMR::lib3mf_defaultpropertyhandler_setbasematerial(defaults, groupId, materialOf.at(first)),
                      "setting the default material");
    }
    NMR::PLib3MFModelBuildItem* item = nullptr;
    Lib3mf::check(NMR::lib3mf_model_addbuilditem(model, object, nullptr, &item), "adding the build item");
    lib.keep(item);
    NMR::PLib3MFModelWriter* writer = nullptr;
    Lib3mf::check(NMR::lib3mf_model_querywriter(model, "3mf", &writer), "making a writer");
    lib.keep(writer);
    ULONG64 size = 0;
    Lib3mf::check(NMR::lib3mf_writer_getstreamsize(writer, &size), "sizing the file", writer);
    Bytes out(static_cast<std::size_t>(size));
    Lib3mf::check(NMR::lib3mf_writer_writetobuffer(writer, out.data(), size), "writing the file", writer);
    return out;
}

}  // namespace

MeshFormat meshFormatOf(const std::string& path) {
    const ExportFormat* format = exportFormatOf(path);
    if (format != nullptr && format->kind == ExportKind::Mesh) {
        if (format->extension == ".stl") return MeshFormat::Stl;
        if (format->extension == ".off") return MeshFormat::Off;
        if (format->extension == ".obj") return MeshFormat::Obj;
        return MeshFormat::ThreeMf;
    }
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    throw Error(SourceLocation{path, 0, 0}, "cannot export to '" + ext + "' (expected " + extensionList(ExportKind::Mesh) + ")");
}

std::vector<unsigned char> meshBytes(const mesh::Mesh& mesh, MeshFormat format, std::span<const glm::vec4> colors) {
    switch (format) {
        case MeshFormat::Stl: return stl(mesh);
        case MeshFormat::Off: return off(mesh);
        case MeshFormat::Obj: return obj(mesh);
        case MeshFormat::ThreeMf: return threeMf(mesh, colors);
    }
    return {};
}

StagedFile stageMesh(const std::string& path, const mesh::Mesh& mesh, std::span<const glm::vec4> colors) {
    const MeshFormat format = meshFormatOf(path);
    std::vector<unsigned char> bytes;
    try {
        bytes = meshBytes(mesh, format, colors);
    } catch (const Error& e) {
        throw Error(SourceLocation{path, 0, 0}, std::string("cannot write mesh (") + e.what() + ")");
    }
    return StagedFile::write(path, "mesh", bytes);
}

}  // namespace strata::io
