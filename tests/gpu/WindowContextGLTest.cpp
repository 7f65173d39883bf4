#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "strata/gpu/Check.h"
#include "strata/gpu/Gl.h"
#include "strata/gpu/WindowContext.h"

using namespace strata;

// Needs an X display (CI: xvfb-run); skipped without one.
TEST(WindowContext, OpensA45CoreWindowAndClearsIt) {
    if (std::getenv("DISPLAY") == nullptr) GTEST_SKIP() << "no DISPLAY (run under xvfb-run to test GLFW windows)";
    gpu::WindowContext window({.width = 32, .height = 24, .title = "strata test", .visible = false, .debug = true});
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_EQ(window.framebufferWidth(), 32);
    EXPECT_EQ(window.framebufferHeight(), 24);

    glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    std::vector<unsigned char> pixel(4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(5, 5, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel.data());
    EXPECT_EQ(pixel, (std::vector<unsigned char>{0, 255, 0, 255}));
    EXPECT_NO_THROW(gpu::checkErrors());
}

// In a child process: GLFW stays initialised once a window has opened, so
// this must not share a process with the test above.
TEST(WindowContext, NoDisplayIsAOneLineError) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    auto openOnMissingDisplay = [] {
        setenv("DISPLAY", ":4999", 1);  // a display that cannot exist
        try {
            gpu::WindowContext window({.width = 8, .height = 8, .visible = false});
        } catch (const Error& e) {
            const std::string what = e.what();
            const bool oneLine = what.rfind("GLFW: ", 0) == 0 && what.find('\n') == std::string::npos;
            std::fprintf(stderr, "%s\n", what.c_str());
            std::exit(oneLine ? 0 : 2);
        }
        std::exit(1);  // a window opened
    };
    EXPECT_EXIT(openOnMissingDisplay(), ::testing::ExitedWithCode(0), "GLFW: ");
}
