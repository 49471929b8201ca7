// Outputs are written to a temporary file beside the target and renamed over it, so a failed
// or interrupted run never leaves a half-written file behind.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace hrad {

/// Calls `write` with a stream to `path`.tmp-XXXX, then renames it to `path`. On any error
/// (from `write` or the file system) the temporary file is removed and an hrad::Error naming
/// `path` is thrown.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           bool binary = false);

/// The same for a writer that needs a file name (libpng, OpenMesh): `write` gets the temporary path.
void write_path_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write);

}  // namespace hrad
