#include "CsgModules.h"

#include <unordered_map>

namespace strata::scene {

Module moduleNamed(std::string_view name) {
    static const std::unordered_map<std::string_view, Module> modules = {
        {"group", Module::Group},
        {"union", Module::Union},
        {"render", Module::Render},
        {"assign", Module::Assign},
        {"intersection", Module::Intersection},
        {"difference", Module::Difference},
        {"multmatrix", Module::Multmatrix},
        {"color", Module::Color},
        {"hull", Module::Hull},
        {"minkowski", Module::Minkowski},
        {"resize", Module::Resize},
        {"projection", Module::Projection},
        {"square", Module::Square},
        {"circle", Module::Circle},
        {"polygon", Module::Polygon},
        {"text", Module::Text},
        {"offset", Module::Offset},
        {"linear_extrude", Module::LinearExtrude},
        {"rotate_extrude", Module::RotateExtrude},
        {"cube", Module::Cube},
        {"sphere", Module::Sphere},
        {"cylinder", Module::Cylinder},
        {"polyhedron", Module::Polyhedron},
        {"surface", Module::Surface},
        {"import", Module::Import},
        // OpenSCAD's modules that strata does not draw yet.
        {"roof", Module::Unsupported},
        {"fill", Module::Unsupported},
        {"import_dxf", Module::Unsupported},
        {"import_stl", Module::Unsupported},
        {"import_off", Module::Unsupported},
        {"dxf_linear_extrude", Module::Unsupported},
        {"dxf_rotate_extrude", Module::Unsupported},
        {"child", Module::Unsupported},
        {"children", Module::Unsupported},
        {"parent_module", Module::Unsupported},
        {"intersection_for", Module::Unsupported},
        {"for", Module::Unsupported},
        {"let", Module::Unsupported},
        {"each", Module::Unsupported},
        {"echo", Module::Unsupported},
        {"assert", Module::Unsupported},
        {"textmetrics", Module::Unsupported},
        {"fontmetrics", Module::Unsupported},
        {"virtual", Module::Unsupported},
        {"wrap", Module::Unsupported},
    };
    const auto found = modules.find(name);
    return found == modules.end() ? Module::Unknown : found->second;
}

}  // namespace strata::scene
