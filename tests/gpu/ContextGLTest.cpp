#include <gtest/gtest.h>

#include <string>

#include "strata/gpu/Check.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Gl.h"

using namespace strata;

TEST(Context, GivesAnOpenGL45CoreContext) {
    gpu::Context context;
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45) << context.version();
    EXPECT_NE(profile & GL_CONTEXT_CORE_PROFILE_BIT, 0);
    EXPECT_FALSE(context.renderer().empty());
    EXPECT_FALSE(context.platform().empty());
    EXPECT_NO_THROW(gpu::checkErrors());
}

TEST(Context, DebugContextTurnsAGlErrorIntoAnErrorNamingTheCaller) {
    gpu::Context context(gpu::ContextOptions{.debug = true});
    EXPECT_TRUE(context.debug());
    glBindBuffer(GL_ARRAY_BUFFER, 987654);  // never created: GL_INVALID_OPERATION in core profile
    const int line = __LINE__ + 2;
    try {
        gpu::checkErrors();
        FAIL() << "checkErrors did not throw";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("tests/gpu/ContextGLTest.cpp:" + std::to_string(line) + ": ", 0), 0u) << what;
        EXPECT_NE(what.find("GL_INVALID_OPERATION"), std::string::npos) << what;
    }
    // The error was consumed: the next check is clean.
    EXPECT_NO_THROW(gpu::checkErrors());
}

TEST(Context, GlErrorIsCaughtWithoutDebugOutputToo) {
    gpu::Context context(gpu::ContextOptions{.debug = false});
    EXPECT_FALSE(context.debug());
    glEnable(0x1234);  // not a capability: GL_INVALID_ENUM
    EXPECT_THROW(gpu::checkErrors(), Error);
}

TEST(Context, TwoContextsOnOneThreadCoexist) {
    gpu::Context first;
    {
        gpu::Context second;
        GLuint buffer = 0;
        glCreateBuffers(1, &buffer);
        EXPECT_NE(buffer, 0u);
        glDeleteBuffers(1, &buffer);
    }
    // The display is shared; destroying the second context must not end the first.
    first.makeCurrent();
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    EXPECT_NE(buffer, 0u);
    glDeleteBuffers(1, &buffer);
    EXPECT_NO_THROW(gpu::checkErrors());
}
