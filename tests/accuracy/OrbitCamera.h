#pragma once
// A camera moved around the centre of another at the same distance: azimuth
// and elevation in degrees (azimuth from +x toward +y), for tests that look
// at one model from several odd angles.

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "strata/camera/Camera.h"

namespace strata::accuracy {

inline camera::Camera orbit(const camera::Camera& standard, double azimuth, double elevation,
                            camera::Projection projection) {
    const double distance = glm::length(standard.eye - standard.center);
    const double az = azimuth * std::numbers::pi / 180.0, el = elevation * std::numbers::pi / 180.0;
    camera::Camera c = standard;
    c.eye = c.center + distance * glm::dvec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    c.projection = projection;
    return c;
}

}  // namespace strata::accuracy
