#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "strata/core/Error.h"
#include "strata/io/ImageWriter.h"

namespace fs = std::filesystem;
using namespace strata;

namespace {

// A fresh folder per test, removed afterwards.
class ImageWriterTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("strata-io-" + std::to_string(::getpid()) + "-" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::vector<std::string> filesInDir() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
        return names;
    }

    fs::path dir_;
};

struct ReadBack {
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::string format;
    std::vector<float> floats;
    std::vector<std::uint8_t> bytes;
};

ReadBack readBack(const std::string& path, OIIO::TypeDesc type) {
    // Ask for the stored values: by default OpenImageIO premultiplies PNG colour by alpha on read.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) throw std::runtime_error("cannot read back " + path + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    ReadBack r;
    r.width = spec.width;
    r.height = spec.height;
    r.channels = std::vector<std::string>(spec.channelnames.begin(), spec.channelnames.end());
    r.format = in->format_name();
    const std::size_t n = static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels;
    if (type == OIIO::TypeDesc::FLOAT) {
        r.floats.resize(n);
        in->read_image(0, 0, 0, spec.nchannels, type, r.floats.data());
    } else {
        r.bytes.resize(n);
        in->read_image(0, 0, 0, spec.nchannels, type, r.bytes.data());
    }
    in->close();
    return r;
}

}  // namespace

TEST_F(ImageWriterTest, PngKeepsEveryByteAndRowZeroIsTheTop) {
    constexpr int kW = 5, kH = 3;
    std::vector<std::uint8_t> rgba(kW * kH * 4);
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
            std::uint8_t* p = &rgba[(j * kW + i) * 4];
            p[0] = static_cast<std::uint8_t>(i * 50);
            p[1] = static_cast<std::uint8_t>(j * 100);
            p[2] = 7;
            p[3] = static_cast<std::uint8_t>(j == 1 ? 128 : 255);  // translucent row: must not be un-premultiplied
        }
    io::writePng(path("a.png"), kW, kH, rgba);
    const ReadBack r = readBack(path("a.png"), OIIO::TypeDesc::UINT8);
    EXPECT_EQ(r.format, "png");
    EXPECT_EQ(r.width, kW);
    EXPECT_EQ(r.height, kH);
    EXPECT_EQ(r.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
    EXPECT_EQ(r.bytes, rgba);
    EXPECT_EQ(filesInDir(), std::vector<std::string>{"a.png"});  // no temporary left behind
}

TEST_F(ImageWriterTest, DepthExrHasOneChannelNamedZAndKeepsInfinity) {
    constexpr int kW = 4, kH = 2;
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> depth{1.5f, inf, -0.25f, 3e6f,  // top row
                                   inf, 0.0f, 12.125f, inf};  // bottom row
    io::writeDepthExr(path("z.exr"), kW, kH, depth);
    const ReadBack r = readBack(path("z.exr"), OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(r.format, "openexr");
    EXPECT_EQ(r.width, kW);
    EXPECT_EQ(r.height, kH);
    EXPECT_EQ(r.channels, std::vector<std::string>{"Z"});
    ASSERT_EQ(r.floats.size(), depth.size());
    for (std::size_t k = 0; k < depth.size(); ++k) {
        if (std::isinf(depth[k]))
            EXPECT_TRUE(std::isinf(r.floats[k]) && r.floats[k] > 0) << k;
        else
            EXPECT_EQ(r.floats[k], depth[k]) << k;  // float32 all the way: exact
    }
}

TEST_F(ImageWriterTest, NormalExrHasChannelsRGB) {
    constexpr int kW = 2, kH = 2;
    const std::vector<glm::vec3> normal{{1, 0, 0}, {0, -1, 0}, {0, 0, 0}, {0.6f, 0, 0.8f}};
    io::writeNormalExr(path("n.exr"), kW, kH, normal);
    const ReadBack r = readBack(path("n.exr"), OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(r.channels, (std::vector<std::string>{"R", "G", "B"}));
    ASSERT_EQ(r.floats.size(), 12u);
    for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(r.floats[k * 3 + c], normal[k][c]) << k << "," << c;
}

TEST_F(ImageWriterTest, WritingIntoAMissingFolderThrowsAndLeavesNothing) {
    const std::string target = path("missing/folder/out.png");
    const std::vector<std::uint8_t> rgba(4, 255);
    try {
        io::writePng(target, 1, 1, rgba);
        FAIL() << "wrote into a missing folder";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(target + ": cannot write PNG", 0), 0u) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    EXPECT_FALSE(fs::exists(target));
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(ImageWriterTest, WrongPixelCountThrowsAndLeavesNothing) {
    const std::vector<float> depth(5, 1.0f);
    EXPECT_THROW(io::writeDepthExr(path("z.exr"), 2, 2, depth), Error);
    EXPECT_THROW(io::writeDepthExr(path("z.exr"), 0, 5, depth), Error);
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(ImageWriterTest, UncommittedStagedFilesLeaveNothing) {
    const std::vector<std::uint8_t> rgba(4 * 4, 9);
    const std::vector<float> depth(4, 2.0f);
    {
        auto png = io::stagePng(path("a.png"), 2, 2, rgba);
        auto z = io::stageDepthExr(path("z.exr"), 2, 2, depth);
        // Both are written, as files without a name in the folder: no target
        // yet, and nothing that a kill could leave behind.
        EXPECT_TRUE(filesInDir().empty());
        // A later output fails: the earlier ones must vanish with it.
        EXPECT_THROW(io::stagePng(path("nope/b.png"), 2, 2, rgba), Error);
    }
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(ImageWriterTest, CommitReplacesAnOldFileOnlyAtTheEnd) {
    {
        std::ofstream old(path("a.png"));
        old << "old contents";
    }
    const std::vector<std::uint8_t> rgba(4, 200);
    auto staged = io::stagePng(path("a.png"), 1, 1, rgba);
    EXPECT_EQ(fs::file_size(path("a.png")), 12u);  // still the old file
    staged.commit();
    const ReadBack r = readBack(path("a.png"), OIIO::TypeDesc::UINT8);
    EXPECT_EQ(r.bytes, rgba);
    EXPECT_EQ(filesInDir(), std::vector<std::string>{"a.png"});
}

TEST_F(ImageWriterTest, AFullDiskIsAnErrorAndLeavesNothing) {
    // A file-size limit fails the write as a full disk does (EFBIG instead of
    // ENOSPC); run in a child, whose limit the test process does not share.
    std::vector<std::uint8_t> rgba(64 * 64 * 4);
    std::uint32_t x = 2463534242u;  // xorshift: noise that no PNG filter compresses
    for (std::uint8_t& byte : rgba) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        byte = static_cast<std::uint8_t>(x >> 24);
    }
    const std::string target = path("big.png");
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        std::signal(SIGXFSZ, SIG_IGN);
        const struct rlimit limit {1024, 1024};
        ::setrlimit(RLIMIT_FSIZE, &limit);
        int code = 1;
        try {
            io::writePng(target, 64, 64, rgba);
        } catch (const Error& e) {
            const std::string message = e.what();
            code = message.rfind(target + ": cannot write PNG (File too large)", 0) == 0 ? 0 : 2;
        }
        std::_Exit(code);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no error, 2: another message";
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(ImageWriterTest, LongNamesWorkAndBadTargetsAreRefused) {
    const std::vector<std::uint8_t> rgba(4, 7);
    // The longest name a file system takes (255 bytes) is written like any other.
    const std::string longName = std::string(251, 'n') + ".png";
    io::writePng(path(longName), 1, 1, rgba);
    EXPECT_EQ(filesInDir(), std::vector<std::string>{longName});
    fs::remove(path(longName));

    std::string nul = path("a.png");
    nul.insert(nul.size() - 4, 1, '\0');
    EXPECT_THROW(io::writePng(nul, 1, 1, rgba), Error);
    ASSERT_EQ(::mkfifo(path("fifo.png").c_str(), 0600), 0);
    try {
        io::writePng(path("fifo.png"), 1, 1, rgba);
        ADD_FAILURE() << "wrote over a FIFO";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), path("fifo.png") + ": cannot write PNG (it is not a regular file)");
    }
    EXPECT_EQ(filesInDir(), std::vector<std::string>{"fifo.png"});
}

TEST_F(ImageWriterTest, TemporariesOfKilledProcessesAreRemoved) {
    // What a process killed between naming and renaming its file leaves; a
    // pid past the kernel's limit is never alive.
    std::ifstream limitFile("/proc/sys/kernel/pid_max");
    long pidMax = 4194304;
    limitFile >> pidMax;
    const std::string stale = ".strata-" + std::to_string(pidMax + 1) + "-0.tmp";
    const std::string live = ".strata-" + std::to_string(::getppid()) + "-0.tmp";
    std::ofstream(path(stale)) << "x";
    std::ofstream(path(live)) << "x";
    std::ofstream(path(".strata-notes.tmp")) << "x";
    // A user's files that only look like it, named after the same dead
    // process, and a folder so named: not strata's, left alone.
    const std::string dead = ".strata-" + std::to_string(pidMax + 1);
    const std::vector<std::string> users{dead + "-draft.tmp", dead + "-0.tmp.tmp", dead + "--1.tmp", dead + "-0-1.tmp"};
    for (const std::string& name : users) std::ofstream(path(name)) << "mine";
    fs::create_directory(path(dead + "-1.tmp"));
    io::writePng(path("a.png"), 1, 1, std::vector<std::uint8_t>(4, 1));
    std::vector<std::string> names = filesInDir();
    std::sort(names.begin(), names.end());
    std::vector<std::string> expected{".strata-notes.tmp", live, "a.png", dead + "-1.tmp"};
    expected.insert(expected.end(), users.begin(), users.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(names, expected);
}

TEST_F(ImageWriterTest, CommitAllWritesEveryFileOrPutsBackWhatItReplaced) {
    const std::vector<std::uint8_t> rgba(4, 50);
    std::ofstream(path("a.png")) << "old a";
    {
        std::vector<io::StagedFile> staged;
        staged.push_back(io::stagePng(path("a.png"), 1, 1, rgba));
        staged.push_back(io::stagePng(path("b.png"), 1, 1, rgba));
        staged.push_back(io::stagePng(path("c.png"), 1, 1, rgba));
        // The last target turns into a folder after staging: its rename fails
        // once the first two are in place.
        fs::create_directory(path("c.png"));
        std::ofstream(path("c.png/inside")) << "x";
        try {
            io::commitAll(staged);
            ADD_FAILURE() << "renamed a file onto a folder";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(path("c.png") + ": cannot write (", 0), 0u) << e.what();
        }
    }
    // a.png is the old file again, b.png (new) is gone, nothing else is left.
    std::ifstream a(path("a.png"));
    const std::string aText((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
    EXPECT_EQ(aText, "old a");
    std::vector<std::string> names = filesInDir();
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"a.png", "c.png"}));

    // Without the folder in the way, all three are written.
    fs::remove_all(path("c.png"));
    std::vector<io::StagedFile> staged;
    for (const char* name : {"a.png", "b.png", "c.png"}) staged.push_back(io::stagePng(path(name), 1, 1, rgba));
    io::commitAll(staged);
    for (const char* name : {"a.png", "b.png", "c.png"}) EXPECT_EQ(readBack(path(name), OIIO::TypeDesc::UINT8).bytes, rgba);
    names = filesInDir();
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"a.png", "b.png", "c.png"}));
}
