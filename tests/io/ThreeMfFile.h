#pragma once
// A 3MF file read back through lib3mf's own reader, for the tests that check
// strata's 3MF writer: its first mesh, its first group of base materials and
// the mesh's per-triangle properties; every lib3mf object released at the end.

#include <Model/COM/NMR_DLLInterfaces.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace strata::testing {

class ThreeMfFile {
public:
    explicit ThreeMfFile(std::vector<unsigned char> bytes) : bytes_(std::move(bytes)) {
        check(NMR::lib3mf_createmodel(&model_), "create a model");
        check(NMR::lib3mf_model_queryreader(model_, "3mf", &reader_), "make a reader");
        check(NMR::lib3mf_reader_readfrombuffer(reader_, bytes_.data(), bytes_.size()), "read the file");
        check(NMR::lib3mf_model_getmeshobjects(model_, &meshes_), "list the meshes");
        mesh_ = first(meshes_, "no mesh");
        check(NMR::lib3mf_model_getbasematerials(model_, &groups_), "list the materials");
        BOOL more = false;
        if (NMR::lib3mf_resourceiterator_movenext(groups_, &more) == LIB3MF_OK && more) {
            check(NMR::lib3mf_resourceiterator_getcurrent(groups_, &group_), "read the materials");
        }
        check(NMR::lib3mf_meshobject_createpropertyhandler(mesh_, &properties_), "read the properties");
    }
    ~ThreeMfFile() {
        for (NMR::PLib3MFBase* object : {properties_, group_, groups_, mesh_, meshes_, reader_, model_})
            if (object != nullptr) NMR::lib3mf_release(object);
    }
    ThreeMfFile(const ThreeMfFile&) = delete;
    ThreeMfFile& operator=(const ThreeMfFile&) = delete;

    NMR::PLib3MFModelResource* mesh() const { return mesh_; }
    NMR::PLib3MFModelResource* materials() const { return group_; }  // nullptr when the file has none
    NMR::PLib3MFPropertyHandler* properties() const { return properties_; }

private:
    static void check(LIB3MFRESULT result, const char* what) {
        if (result != LIB3MF_OK) throw std::runtime_error(std::string("lib3mf could not ") + what);
    }
    NMR::PLib3MFModelResource* first(NMR::PLib3MFModelResourceIterator* list, const char* none) {
        BOOL more = false;
        check(NMR::lib3mf_resourceiterator_movenext(list, &more), "walk a list");
        if (!more) throw std::runtime_error(none);
        NMR::PLib3MFModelResource* resource = nullptr;
        check(NMR::lib3mf_resourceiterator_getcurrent(list, &resource), "read a list");
        return resource;
    }

    std::vector<unsigned char> bytes_;
    NMR::PLib3MFModel* model_ = nullptr;
    NMR::PLib3MFModelReader* reader_ = nullptr;
    NMR::PLib3MFModelResourceIterator* meshes_ = nullptr;
    NMR::PLib3MFModelResource* mesh_ = nullptr;
    NMR::PLib3MFModelResourceIterator* groups_ = nullptr;
    NMR::PLib3MFModelResource* group_ = nullptr;
    NMR::PLib3MFPropertyHandler* properties_ = nullptr;
};

}  // namespace strata::testing
