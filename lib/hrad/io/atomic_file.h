// Outputs that never replace an input and never leave anything half-written behind.
//
// A command declares its outputs before any work (OutputFiles::declare), which refuses:
//   * an existing path that is not a regular file ("is a directory", "is a FIFO", ...),
//   * two outputs that are the same file (same device and inode when both exist, the same
//     canonical path otherwise; symbolic links resolved),
//   * an output that is one of the command's inputs (check_inputs, same rule),
//   * an output whose folder cannot be written: a staging folder (".hrad-tmp-XXXXXX") is created
//     right away in the nearest existing folder above each output, so a read-only or missing
//     place fails before the work, not after it.
// While an OutputFiles is alive, write_file_atomically() and write_path_atomically() write a declared
// path (or any path under a declared folder) into its staging folder under the same relative name
// (so files that refer to each other by name, like a CSV and its images, still find each other);
// commit() renames every staged file onto its target, creating missing folders, and removes the
// staging folders. The destructor of an OutputFiles that was not committed (an error, an exception)
// removes what it staged, and so does SIGINT or SIGTERM (a handler unlinks the registered
// temporaries and folders, then dies of the signal as before).
// An output that is a symbolic link to a regular file is written through the link (the link stays).
// Files are created with mode 0666 minus the umask, as any program's outputs.
#pragma once

#include <sys/types.h>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace hrad {

/// Calls `write` with a stream to a temporary file, then renames it to `path`. On any error
/// (from `write` or the file system) the temporary file is removed and an hrad::Error naming
/// `path` is thrown. Inside an OutputFiles that declared `path`, the rename waits for its commit().
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           bool binary = false);

/// The same for a writer that needs a file name (libpng, OpenMesh): `write` gets the temporary path.
void write_path_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write);

/// The path a file written to `path` now lives at: its staged temporary inside an active
/// OutputFiles that covers `path`, else `path` itself (for programs run on files just written).
std::string staged_path(const std::string& path);

/// The pid of a child process writing staged files (a plot script), killed by the signal handler
/// before it removes the temporaries; 0 when none.
void set_output_child(pid_t pid);

class OutputFiles {
 public:
  OutputFiles();
  /// Removes what was staged unless commit() ran.
  ~OutputFiles();
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;

  /// An output file named by `option` ("--out"): checked as described above; hrad::Error naming the
  /// option and the path when refused.
  void declare(const std::string& option, const std::string& path);
  /// An output folder: every file written under it is an output (the folder itself may exist).
  void declare_folder(const std::string& option, const std::string& path);
  /// Refuses when a declared output is the same file as one of `inputs` (description, path), e.g.
  /// {"the scene", "room.obj"}: "--out room.obj is the scene: it would be overwritten".
  void check_inputs(const std::vector<std::pair<std::string, std::string>>& inputs) const;
  /// Renames every staged file onto its target (in declaration order) and removes the staging folders.
  void commit();

  /// The temporary for `path` if this covers it (declared, or under a declared folder), else "".
  std::string temporary_for(const std::string& path);

 private:
  struct Output {
    std::string option, path, target;  ///< as given; with symbolic links resolved
    bool folder = false;
  };
  std::string staging_for(const std::string& existing_ancestor);

  std::vector<Output> outputs_;
  std::map<std::string, std::string> staging_;               ///< existing folder -> its staging folder
  std::vector<std::pair<std::string, std::string>> staged_;  ///< (temporary, target) in write order
  std::vector<std::string> made_folders_;                    ///< folders made inside staging folders
  OutputFiles* previous_ = nullptr;
  bool committed_ = false;
};

}  // namespace hrad
