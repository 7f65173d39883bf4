#pragma once
// The files strata-view opened last, newest first, kept between sessions in
// one text file (a path a line): $XDG_STATE_HOME/strata/recent-files, else
// ~/.local/state/strata/recent-files. A list that cannot be read starts
// empty; one that cannot be written is kept for this session only.

#include <string>
#include <vector>

namespace strata::view {

class RecentFiles {
public:
    static constexpr std::size_t kMax = 10;

    // Where the list is kept for this user; empty when neither
    // XDG_STATE_HOME nor HOME is set (the list then lives in memory).
    static std::string defaultStore();

    // Reads the list kept in `store` (empty: none).
    explicit RecentFiles(std::string store = defaultStore());

    // `path` opened: first in the list (as an absolute path), once, and the
    // list written back. Returns why it could not be written, or "".
    std::string add(const std::string& path);

    const std::vector<std::string>& files() const { return files_; }

private:
    std::string store_;
    std::vector<std::string> files_;
};

}  // namespace strata::view
