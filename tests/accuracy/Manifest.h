#pragma once
// The accuracy corpus's manifest (tests/accuracy/scenes.txt, written by
// generate.py): one line per scene and camera,
//
//   stack_paper_3.csg stack p 96x96 0.137,-0.211,60,0.137,-0.211,0 fov=30 nonconvex-stack
//   ^ scene file       ^family ^p|o ^W x H ^eye and center (CONTRACT's --camera) ^options
//
// '#' starts a comment; blank lines are skipped. Options: `fov=DEG` (default
// the contract's 22.5) and flags, e.g. `nonconvex-stack` (the shot must FAIL
// the accuracy bounds when every operand gets one peel layer).

#include <iosfwd>
#include <string>
#include <vector>

#include "strata/camera/Camera.h"

namespace strata::accuracy {

struct Shot {
    std::string scene;                // file name, relative to the manifest's scenes/ folder
    std::string family;               // stack, deep, nary, nonconvex, through, thin, near, inside, transform
    camera::Camera camera;            // eye, center, projection, fov, image size
    std::vector<std::string> flags;
    int line = 0;                     // in the manifest
    int index = 0;                    // this scene's k-th shot, from 0
    std::string name;                 // "<scene stem>_<p|o><index>": letters, digits, '_' only

    bool has(const std::string& flag) const;
};

// gtest prints a shot by its name.
void PrintTo(const Shot& shot, std::ostream* out);

// Reads the manifest. Throws strata::Error "path:line:col: message" on a
// malformed line (wrong field count, bad number, size or projection).
std::vector<Shot> loadManifest(const std::string& path);

}  // namespace strata::accuracy
