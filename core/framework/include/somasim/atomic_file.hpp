#pragma once
/// @file
/// Writing a file whole or not at all: a reader, or a run killed meanwhile, sees the old file or
/// the new one, never half of one.
#include <filesystem>
#include <string_view>

namespace somasim {

/// Writes `text` to a temporary file beside `file`, flushes it to disk and renames it over
/// `file` (the folder's entry is synced too, where the file system allows). Throws
/// std::runtime_error naming the file when any step fails; the temporary file is then removed.
void write_file_atomically(const std::filesystem::path& file, std::string_view text);

}  // namespace somasim
