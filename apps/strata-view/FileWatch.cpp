#include "FileWatch.h"

#include <sys/stat.h>

#include <utility>

namespace strata::view {

bool FileStamp::operator==(const FileStamp& other) const {
    return exists == other.exists && device == other.device && inode == other.inode && size == other.size &&
           modified.tv_sec == other.modified.tv_sec && modified.tv_nsec == other.modified.tv_nsec;
}

FileStamp stampOf(const std::string& path) {
    struct stat st {};
    FileStamp stamp;
    if (::stat(path.c_str(), &st) != 0) return stamp;
    stamp.exists = true;
    stamp.device = st.st_dev;
    stamp.inode = st.st_ino;
    stamp.size = st.st_size;
    stamp.modified = st.st_mtim;
    return stamp;
}

FileWatch::FileWatch(std::string path) : path_(std::move(path)), last_(stampOf(path_)) {}

bool FileWatch::changed() {
    const FileStamp now = stampOf(path_);
    missingPolls_ = now.exists ? 0 : missingPolls_ + 1;
    if (!now.exists || now == last_) return false;
    last_ = now;
    return true;
}

}  // namespace strata::view
