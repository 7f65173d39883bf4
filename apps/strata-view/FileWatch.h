#pragma once
// Notices that a file was saved, by polling stat(). Editors save by writing a
// new file and renaming it over the old one, so the path is stat()ed afresh
// each time (no descriptor is kept): a rename shows as a new inode, an
// in-place write as a new size or modification time.

#include <sys/types.h>

#include <ctime>
#include <string>

namespace strata::view {

struct FileStamp {
    bool exists = false;
    dev_t device = 0;
    ino_t inode = 0;
    off_t size = 0;
    std::timespec modified{};

    bool operator==(const FileStamp& other) const;
};

FileStamp stampOf(const std::string& path);

class FileWatch {
public:
    FileWatch() = default;
    explicit FileWatch(std::string path);

    // True once per change since the last call (or construction). While the
    // file is missing (between an editor's unlink and rename) nothing changes:
    // the file's return is the change.
    bool changed();
    // How many calls of changed() in a row found no file: 0 while it is there.
    int missingPolls() const { return missingPolls_; }
    const std::string& path() const { return path_; }

private:
    std::string path_;
    FileStamp last_;
    int missingPolls_ = 0;
};

}  // namespace strata::view
