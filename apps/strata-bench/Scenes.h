#pragma once
// The benchmark's scenes, built in code from a seed so every run draws the
// same triangles. Each takes K, the number of operands that make it hard.
//
//   cheese        a cube minus K spheres ($fn=32: 32 segments x 16 rings)
//                 at random positions over it
//   stack         a slab minus K spheres lined up on the camera's view ray
//                 through the slab's centre: depth complexity K on one pixel
//   intersection  K slightly offset spheres intersected
//   deep          a left-deep chain of K leaves (spheres and cubes) under
//                 unions, differences and, now and then, an intersection
//   tori          a cube minus K tori (32 x 16, polyhedron leaves: non-convex,
//                 up to 4 surfaces on a ray) at random positions and angles
//   mesh          a trefoil-knot tube of 131072 triangles (one polyhedron
//                 leaf, as an imported mesh would be) minus K spheres along it
//   blowup        K unions of two overlapping spheres, intersected: for
//                 OpenCSG, a sum of 2^K products of K spheres (past
//                 OpenSCAD's 200,000-element limit from K = 12)

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "strata/camera/Camera.h"
#include "strata/scene/Tree.h"

namespace strata::bench {

struct BenchScene {
    scene::Tree tree;
    // A camera the scene needs (stack: the spheres lie on its view ray);
    // empty: OpenSCAD's default view fitted to the scene.
    std::optional<camera::Camera> camera;
};

// The scene names, in the order the table lists them.
const std::vector<std::string>& sceneNames();

// Throws strata::Error for an unknown name or K < 1.
// `base` carries the image size (and, for stack, the field of view).
BenchScene makeScene(std::string_view name, int k, std::uint32_t seed, const camera::Camera& base);

}  // namespace strata::bench
