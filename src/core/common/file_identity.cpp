#include "lane_keeping/common/file_identity.h"

#include <sys/stat.h>

#include <filesystem>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace fs = std::filesystem;

namespace {

fs::path canonicalOf(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal() : p;
}

}  // namespace

bool sameFile(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  return canonicalOf(a) == canonicalOf(b);
}

bool isInside(const std::string& path, const std::string& dir) {
  const fs::path p = canonicalOf(path), d = canonicalOf(dir);
  auto pi = p.begin();
  for (auto di = d.begin(); di != d.end(); ++di, ++pi) {
    if (di->empty()) continue;  // a trailing separator
    if (pi == p.end() || *pi != *di) return false;
  }
  return true;
}

std::string whyNotRegularFile(const std::string& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0) {
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(path, ec))) {
      return "is a dangling symbolic link to '" + fs::read_symlink(path, ec).string() + "'";
    }
    return "does not exist";
  }
  if (S_ISREG(s.st_mode)) return "";
  if (S_ISDIR(s.st_mode)) return "is a directory, not a file";
  if (S_ISCHR(s.st_mode)) return "is a character device, not a regular file";
  if (S_ISBLK(s.st_mode)) return "is a block device, not a regular file";
  if (S_ISFIFO(s.st_mode)) return "is a pipe (FIFO), not a regular file";
  if (S_ISSOCK(s.st_mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

void refuseOutputAmongInputs(const PathArgument& output, const std::vector<PathArgument>& inputs,
                             bool output_is_directory) {
  for (const auto& [option, path] : inputs) {
    if (path.empty()) continue;
    if (sameFile(output.second, path)) {
      throw UsageError(output.first + " " + output.second + " is the file given as " + option + " " + path +
                       ": writing it would replace that input; choose another output");
    }
    if (output_is_directory && isInside(path, output.second)) {
      throw UsageError(output.first + " " + output.second + " holds " + option + " " + path +
                       ": the output directory is replaced as a whole, which would remove that input; choose "
                       "another output directory");
    }
  }
}

}  // namespace lane_keeping
