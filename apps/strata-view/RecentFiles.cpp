#include "RecentFiles.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace strata::view {
namespace {

namespace fs = std::filesystem;

// A line of the store that can name a file: absolute, no control bytes, not absurdly long.
bool plausible(const std::string& line) {
    if (line.empty() || line.front() != '/' || line.size() > 4096) return false;
    return std::none_of(line.begin(), line.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

}  // namespace

std::string RecentFiles::defaultStore() {
    const char* state = std::getenv("XDG_STATE_HOME");
    if (state != nullptr && state[0] == '/') return (fs::path(state) / "strata" / "recent-files").string();
    const char* home = std::getenv("HOME");
    if (home != nullptr && home[0] == '/') return (fs::path(home) / ".local" / "state" / "strata" / "recent-files").string();
    return {};
}

RecentFiles::RecentFiles(std::string store) : store_(std::move(store)) {
    if (store_.empty()) return;
    std::error_code ec;
    if (!fs::is_regular_file(store_, ec) || fs::file_size(store_, ec) > 64 * 1024) return;
    std::ifstream in(store_);
    for (std::string line; files_.size() < kMax && std::getline(in, line);)
        if (plausible(line) && std::find(files_.begin(), files_.end(), line) == files_.end()) files_.push_back(line);
}

std::string RecentFiles::add(const std::string& path) {
    std::error_code ec;
    const std::string absolute = fs::absolute(path, ec).lexically_normal().string();
    if (ec || !plausible(absolute)) return {};
    files_.erase(std::remove(files_.begin(), files_.end(), absolute), files_.end());
    files_.insert(files_.begin(), absolute);
    if (files_.size() > kMax) files_.resize(kMax);
    if (store_.empty()) return {};

    // Written beside the store and renamed over it: a reader never sees half a list.
    const fs::path store(store_);
    fs::create_directories(store.parent_path(), ec);
    const fs::path temporary = store.parent_path() / (".recent-files." + std::to_string(::getpid()) + ".tmp");
    {
        std::ofstream out(temporary, std::ios::trunc);
        for (const std::string& file : files_) out << file << '\n';
        out.flush();
        if (!out) {
            fs::remove(temporary, ec);
            return "cannot keep the recent files in " + store_;
        }
    }
    fs::rename(temporary, store, ec);
    if (ec) {
        fs::remove(temporary, ec);
        return "cannot keep the recent files in " + store_;
    }
    return {};
}

}  // namespace strata::view
