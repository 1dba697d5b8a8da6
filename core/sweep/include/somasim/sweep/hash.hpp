#pragma once
/// @file
/// Content hashes for sweep bookkeeping: 64-bit FNV-1a (Fowler–Noll–Vo, offset basis
/// 0xcbf29ce484222325, prime 0x100000001b3) over the bytes. Not cryptographic: it tells whether
/// a stored resolved experiment equals the one a job expects, nothing more.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace somasim::sweep {

std::uint64_t fnv1a64(std::string_view bytes);

/// "fnv1a64:" followed by 16 lower-case hex digits.
std::string content_hash(std::string_view bytes);

/// content_hash() of a file's bytes; nullopt when it cannot be read.
std::optional<std::string> file_hash(const std::filesystem::path& file);

}  // namespace somasim::sweep
