#pragma once
/// @file
/// Reading a shared library's exported symbols from its file, without loading it: dlopen runs
/// a library's constructors, so a file is checked this way before it is ever opened (a plugin
/// library must export the entry point; anything else is refused unopened).
#include <filesystem>
#include <string>

namespace somasim {

/// Whether `file` is a 64-bit ELF shared object for this machine whose dynamic symbol table
/// defines a global function `symbol`. False with `why` set (one line, e.g. "not an ELF file",
/// "built for another machine", "no entry point 'x' among its dynamic symbols") otherwise.
/// Reads at most the ELF header, the section headers and the dynamic symbol and string
/// tables, each checked against the file's size; files over 1 GiB are refused.
bool elf_exports_function(const std::filesystem::path& file, const std::string& symbol,
                          std::string& why);

}  // namespace somasim
