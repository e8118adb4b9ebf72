#include "lane_keeping/gap/report/report_directory.h"

#include <fcntl.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace fs = std::filesystem;

namespace {

constexpr const char* kStagingMark = ".partial-";

bool startsWith(const std::string& text, const std::string& prefix) { return text.compare(0, prefix.size(), prefix) == 0; }

/// The report directory is replaced as a whole on publish(): anything in it that is not a report's (a
/// user's other files, an input of the run) is refused, before the work and again before the move.
void refuseForeignFiles(const fs::path& dir, const std::string& target);

}  // namespace

const std::vector<std::string>& ReportDirectory::reportFiles() {
  static const std::vector<std::string> files{"report.json", "report.json.tmp", "report.md",   "residuals.csv",
                                              "spectrum.csv", "overlay.csv",    "residuals.png", "spectrum.png",
                                              "overlay.png",  "ranking.png"};
  return files;
}

namespace {

void refuseForeignFiles(const fs::path& dir, const std::string& target) {
  std::error_code ec;
  const auto& own = ReportDirectory::reportFiles();
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string file = entry.path().filename().string();
    std::error_code type_error;
    if (!entry.is_regular_file(type_error) || std::find(own.begin(), own.end(), file) == own.end()) {
      throw UsageError("--report " + target + ": holds '" + file +
                       "', which is not part of a gap report; the report directory is replaced as a whole, so "
                       "give a new or empty directory, or one that holds only an earlier report");
    }
  }
  if (ec) throw InputError("--report " + target + ": cannot list the directory: " + ec.message());
}

/// The previous report must be replaceable when the run ends: found now, not after the diagnosis. Renaming a
/// directory takes write permission on it (its ".." changes) and on its parent, and neither may be
/// immutable or append-only (chattr, which binds root too).
void refuseUnreplaceable(const fs::path& dir, const std::string& target) {
  for (const fs::path& p : {dir, dir.parent_path()}) {
    if (::access(p.c_str(), W_OK | X_OK) != 0) {
      throw InputError("--report " + target + ": " + p.string() + " is not writable (" + std::strerror(errno) +
                       "): the report could not replace the previous one");
    }
    const int fd = ::open(p.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    int flags = 0;
    if (fd >= 0 && ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0 && (flags & (FS_IMMUTABLE_FL | FS_APPEND_FL))) {
      ::close(fd);
      throw InputError("--report " + target + ": " + p.string() +
                       " is immutable or append-only (chattr): the report could not replace the previous one");
    }
    if (fd >= 0) ::close(fd);
  }
}

}  // namespace

ReportDirectory::ReportDirectory(const std::string& target) : target_(target) {
  if (target.empty()) throw UsageError("--report: an empty directory name");
  std::error_code ec;
  // The rename works on the real directory: a symbolic link to it stays a link to the new report.
  fs::path resolved = fs::weakly_canonical(fs::absolute(target), ec);
  if (ec) throw InputError("--report " + target + ": " + ec.message());
  if (resolved.filename().empty()) resolved = resolved.parent_path();  // "dir/"
  resolved_ = resolved.string();
  const fs::path parent = resolved.parent_path();
  const std::string name = resolved.filename().string();
  if (name.empty() || name == "." || name == ".." || resolved == resolved.root_path()) {
    throw UsageError("--report " + target + ": the report directory must be a directory of its own, not the root");
  }
  const fs::file_status status = fs::status(resolved, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) {
      throw UsageError("--report " + target + ": exists and is not a directory");
    }
    refuseForeignFiles(resolved, target);
    refuseUnreplaceable(resolved, target);
  }
  fs::create_directories(parent, ec);
  if (ec) throw InputError("--report " + target + ": cannot create " + parent.string() + ": " + ec.message());

  // The lock: one writer at a time. Reopened until the file locked is the one at the path, so that a
  // writer that unlinks it on leaving cannot let two others lock different files.
  lock_path_ = (parent / ("." + name + ".lock")).string();
  for (int attempt = 0;; ++attempt) {
    lock_fd_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd_ < 0) {
      throw InputError("--report " + target + ": cannot write in " + parent.string() + " (" + std::strerror(errno) + ")");
    }
    if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(lock_fd_);
      lock_fd_ = -1;
      if (error == EWOULDBLOCK) {
        throw UsageError("--report " + target + ": another run is writing a report there (it holds " + lock_path_ +
                         "); wait for it to finish or choose another directory");
      }
      throw InputError("--report " + target + ": cannot lock " + lock_path_ + ": " + std::strerror(error));
    }
    struct stat held {}, named {};
    if (::fstat(lock_fd_, &held) == 0 && ::stat(lock_path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      break;
    }
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (attempt > 100) throw InputError("--report " + target + ": cannot lock " + lock_path_ + " (it keeps changing)");
  }
  // Staging directories of runs that died before publishing (no live run holds the lock now).
  const std::string stale_prefix = "." + name + kStagingMark;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    if (startsWith(entry.path().filename().string(), stale_prefix)) fs::remove_all(entry.path(), ec);
  }
  std::string pattern = (parent / (stale_prefix + "XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    const int error = errno;
    releaseLock();
    throw InputError("--report " + target + ": cannot create a directory in " + parent.string() + " (" +
                     std::strerror(error) + ")");
  }
  staging_ = pattern;
  ::chmod(staging_.c_str(), 0755);  // mkdtemp makes it 0700; a report is as readable as any output
}

ReportDirectory::~ReportDirectory() {
  if (!published_ && !staging_.empty()) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
  releaseLock();
}

void ReportDirectory::releaseLock() {
  if (lock_fd_ < 0) return;
  ::unlink(lock_path_.c_str());  // while held: the next writer creates a fresh one (see the constructor)
  ::close(lock_fd_);
  lock_fd_ = -1;
}

void ReportDirectory::publish() {
  if (published_) return;
  std::error_code ec;
  const bool previous = fs::exists(fs::symlink_status(resolved_, ec));
  if (previous) {
    try {
      refuseForeignFiles(resolved_, target_);
    } catch (const LaneKeepingError& e) {
      published_ = true;  // the report stays in its staging directory, which the message names
      throw InputError(std::string(e.what()) + " (files appeared there during the run); the report is in " + staging_);
    }
  }
  int result = previous ? ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, resolved_.c_str(), RENAME_EXCHANGE)
                        : ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, resolved_.c_str(), RENAME_NOREPLACE);
  if (result != 0 && (errno == EINVAL || errno == ENOSYS)) {
    // A file system without renameat2's flags (NFS, some FUSE): the previous report is moved aside first,
    // so for a moment there is none; the lock still keeps every other writer out.
    if (previous) {
      const std::string aside = staging_ + ".previous";
      if (::rename(resolved_.c_str(), aside.c_str()) != 0) {
        throw InputError("--report " + target_ + ": cannot move the previous report aside: " + std::strerror(errno));
      }
      result = ::rename(staging_.c_str(), resolved_.c_str());
      if (result != 0) {
        const int error = errno;
        ::rename(aside.c_str(), resolved_.c_str());  // the previous report back
        throw InputError("--report " + target_ + ": cannot move the report into place: " + std::strerror(error));
      }
      fs::remove_all(aside, ec);
      published_ = true;
      return;
    }
    result = ::rename(staging_.c_str(), resolved_.c_str());
  }
  if (result != 0) {
    const int error = errno;
    published_ = true;  // kept where the message says
    throw InputError("--report " + target_ + ": cannot move the report into place (" + std::strerror(error) +
                     "); it is in " + staging_);
  }
  published_ = true;
  if (previous) fs::remove_all(staging_, ec);  // after the exchange, the previous report
}

}  // namespace lane_keeping
