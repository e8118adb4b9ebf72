#pragma once
/// Which file a path names, for the tools' checks on their arguments: an output that is one of the
/// inputs (`lk_simulate --config my.yaml --out my.yaml` replaced the configuration with the log), a
/// held-out log that is the training log (`--holdout` scored in-sample), and inputs that are not files
/// (`--config DIR` read as "basic_filebuf::underflow", `path.waypoints: /dev/zero` read forever).
#include <string>
#include <utility>
#include <vector>

namespace lane_keeping {

/// Whether `a` and `b` name the same file: the same device and inode when both exist (a symbolic link, a
/// hard link, another spelling: `./a.csv`, `dir/../a.csv`), else the same weakly canonical path.
bool sameFile(const std::string& a, const std::string& b);

/// Whether `path` is `dir` or lies below it, compared by canonical paths (symbolic links resolved).
bool isInside(const std::string& path, const std::string& dir);

/// "" if `path` names a regular file (after symbolic links), else why not, for a message: "does not
/// exist", "is a directory", "is a character device, not a regular file", "is a dangling symbolic link
/// to 'x'", ...
std::string whyNotRegularFile(const std::string& path);

/// A named argument: the option and the path it gave ("--config", "my.yaml").
using PathArgument = std::pair<std::string, std::string>;

/// Throws UsageError if `output` (given as `output_option`) is one of `inputs` or, when
/// `output_is_directory`, holds one of them: writing it would replace or remove that input.
void refuseOutputAmongInputs(const PathArgument& output, const std::vector<PathArgument>& inputs,
                             bool output_is_directory = false);

}  // namespace lane_keeping
