#pragma once
// The camera of docs/contract.md ("Camera"): OpenSCAD's conventions, Z up.
// Pure math, shared by the GPU renderer and the CPU reference so both sample
// exactly the same rays. Its own room (strata_camera); the namespace is the
// renderer's, whose API takes a Camera.

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "strata/mesh/Mesh.h"

namespace strata::camera {

enum class Projection { Perspective, Orthographic };

struct Ray {
    glm::dvec3 origin;
    glm::dvec3 direction;  // unit length
};

struct Camera {
    glm::dvec3 eye{0.0, -10.0, 0.0};
    glm::dvec3 center{0.0, 0.0, 0.0};
    double fovDegrees = 22.5;  // vertical field of view
    Projection projection = Projection::Perspective;
    int width = 512;
    int height = 512;

    // f, r, u of the contract: f = normalize(center - eye), r = normalize(cross(f, z))
    // (with (0,1,0) as up when f is parallel to Z), u = cross(r, f).
    glm::dvec3 forward() const;
    glm::dvec3 right() const;
    glm::dvec3 up() const;

    // The ray through pixel (i, j): column i from the left, row j from the TOP,
    // sampled at the pixel centre (i + 0.5, j + 0.5).
    Ray ray(int i, int j) const;

    // View-space depth of a world point: dot(p - eye, f).
    double viewDepth(const glm::dvec3& p) const;

    // gluLookAt(eye, center, up()).
    glm::dmat4 viewMatrix() const;
    // gluPerspective(fov, W/H, near, far) or the matching glOrtho with
    // h = |center - eye| * tan(fov/2). OpenGL's bottom-up rows: flip on read-back.
    glm::dmat4 projectionMatrix(double zNear, double zFar) const;
};

// Surfaces along one view ray whose view depths differ by no more than this
// count as one place, the coincidence tolerance (docs/algorithm.md,
// "Coincident surfaces"): 2^-20 of the largest magnitude that the GPU's float
// depths and positions carry in this view (the eye's coordinates, the box's
// corners and their view depths), so it scales with the scene and the
// camera. Faces in one plane get one depth on the GPU whatever their leaf
// (their fragments meet one float plane: render::FacePlanes), so the
// tolerance only has to hold the rounding of a float (2^-23, a few times
// over) between surfaces that exact arithmetic puts at one depth. The GPU
// evaluator and the CPU reference take the same value for one frame.
// Positive, also for an empty box.
double coincidenceTolerance(const Camera& camera, const mesh::Bounds& box);

// OpenSCAD's --camera: 6 numbers (eye, center) or 7 (gimbal: translate, rotate,
// distance). Throws strata::Error on any other count.
Camera cameraFromArguments(const std::vector<double>& numbers, const Camera& base);

// OpenSCAD's default view (--viewall --autocenter) fitted to `bounds`: the
// gimbal rotation (55, 0, 25), centred on the bounds, at the distance that
// OpenSCAD's viewAll picks for the camera's field of view.
Camera defaultCamera(const mesh::Bounds& bounds, const Camera& base);

}  // namespace strata::camera
