// Reading an input file whole, without ever blocking: a FIFO with no writer or a device given as a
// scene or solution is refused with a message instead of hanging the program.
#pragma once

#include <sys/types.h>
#include <string>

namespace hrad {

/// "is a directory", "is a FIFO (named pipe), not a regular file", ...: what a non-regular file is.
std::string file_kind(mode_t mode);

/// The bytes of the regular file `path`. It is opened with O_NONBLOCK and checked with fstat before
/// any read, so a FIFO, a device or a folder is an hrad::Error naming `path` ("path: cannot read: is
/// a FIFO ..."), as is a missing file ("path: cannot open file: No such file or directory").
std::string read_input_file(const std::string& path);

}  // namespace hrad
