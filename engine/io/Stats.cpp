#include "strata/io/Stats.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "strata/io/Json.h"

namespace strata::io {

namespace {
// Milliseconds to a tenth of a microsecond: enough, and short to read.
double ms(double v) { return std::round(v * 1e4) / 1e4; }
}  // namespace

std::string statsJson(const RunStats& s, int indent) {
    const render::FrameStats& f = s.frame;
    JsonWriter json(indent);
    json.beginObject();
    json.key("scene").value(s.scene);
    json.key("width").value(s.width);
    json.key("height").value(s.height);
    json.key("renderer").value(s.renderer);

    json.key("time_ms").beginObject();
    json.key("parse").value(ms(s.parseMs));
    json.key("geometry").value(ms(s.geometryMs));
    json.key("context").value(ms(s.contextMs));
    json.key("upload").value(ms(s.uploadMs));
    json.key("peel").value(ms(f.peelMs));
    json.key("evaluate").value(ms(f.evaluateMs));
    json.key("normal").value(ms(f.normalMs));
    json.key("plain").value(ms(f.plainMs));
    json.key("shade").value(ms(f.shadeMs));
    json.key("readback").value(ms(f.readbackMs));
    json.key("frame").value(ms(f.totalMs));
    json.key("write").value(ms(s.writeMs));
    if (s.exportMs >= 0) json.key("export").value(ms(s.exportMs));
    if (s.exportSampleMs >= 0) json.key("export_sample").value(ms(s.exportSampleMs));
    if (s.exportContourMs >= 0) json.key("export_contour").value(ms(s.exportContourMs));
    json.key("total").value(ms(s.totalMs));
    json.endObject();

    json.key("operands").value(f.operands);
    json.key("leaves").value(s.leaves);
    json.key("dimensions").value(s.dimensions);
    json.key("triangles").value(static_cast<std::uint64_t>(s.triangles));
    json.key("layers_per_operand").beginArray(/*oneLine=*/true);
    for (int layers : f.layersPerLeaf) json.value(layers);
    json.endArray();
    const int maxLayers = f.layersPerLeaf.empty() ? 0 : *std::max_element(f.layersPerLeaf.begin(), f.layersPerLeaf.end());
    json.key("layers_max").value(maxLayers);
    json.key("layers_total").value(std::accumulate(f.layersPerLeaf.begin(), f.layersPerLeaf.end(), 0));
    json.key("texture_bytes").value(static_cast<std::uint64_t>(f.textureBytes));
    json.key("covered_pixels").value(static_cast<std::uint64_t>(f.coveredPixels));
    json.key("unresolved_pixels").value(static_cast<std::uint64_t>(f.unresolvedPixels));
    json.key("tiles").value(f.tiles);
    json.key("plain_frame").value(f.plain);
    json.key("plain_tied_leaves").value(static_cast<std::uint64_t>(f.tiedLeaves));
    json.key("plain_tied_triangles").value(static_cast<std::uint64_t>(f.tiedTriangles));
    json.key("plain_beside_leaves").value(static_cast<std::uint64_t>(f.plainBesideLeaves));
    json.key("peel_passes").value(f.peelPasses);
    json.key("list_peeled_operands").value(f.listPeeledOperands);

    json.key("notes").beginArray();
    for (const std::string& note : f.notes) json.value(note);
    json.endArray();
    json.key("warnings").beginArray();
    for (const std::string& warning : s.warnings) json.value(warning);
    json.endArray();
    json.key("unsupported").beginObject();
    for (const auto& [name, count] : s.unsupported) json.key(name).value(count);
    json.endObject();
    json.endObject();
    return json.str();
}

}  // namespace strata::io
