#include "somasim/elf_symbols.hpp"

#include <elf.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <vector>

namespace somasim {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kMaxFileBytes = 1ULL << 30;

#if defined(__x86_64__)
constexpr std::uint16_t kMachine = EM_X86_64;
#elif defined(__aarch64__)
constexpr std::uint16_t kMachine = EM_AARCH64;
#else
constexpr std::uint16_t kMachine = EM_NONE;  // unknown: every library is "for another machine"
#endif

// Bounded reads of a file of known size.
class Reader {
 public:
  Reader(const fs::path& file, std::uint64_t size) : in_(file, std::ios::binary), size_(size) {}
  bool ok() const { return static_cast<bool>(in_); }
  // `count` bytes at `offset`, or nothing when they lie (partly) beyond the end.
  std::optional<std::vector<char>> bytes(std::uint64_t offset, std::uint64_t count) {
    if (offset > size_ || count > size_ - offset) return std::nullopt;
    std::vector<char> out(static_cast<std::size_t>(count));
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(out.data(), static_cast<std::streamsize>(count));
    if (!in_) return std::nullopt;
    return out;
  }
  template <class T>
  std::optional<T> value(std::uint64_t offset) {
    const auto b = bytes(offset, sizeof(T));
    if (!b) return std::nullopt;
    T t;
    std::memcpy(&t, b->data(), sizeof(T));
    return t;
  }

 private:
  std::ifstream in_;
  std::uint64_t size_;
};

}  // namespace

bool elf_exports_function(const fs::path& file, const std::string& symbol, std::string& why) {
  std::error_code ec;
  const auto status = fs::status(file, ec);
  if (ec || !fs::is_regular_file(status)) {
    why = "not a regular file";
    return false;
  }
  const std::uint64_t size = fs::file_size(file, ec);
  if (ec || size > kMaxFileBytes) {
    why = "larger than 1 GiB";
    return false;
  }
  Reader r(file, size);
  if (!r.ok()) {
    why = "cannot be read";
    return false;
  }
  const auto eh = r.value<Elf64_Ehdr>(0);
  if (!eh || std::memcmp(eh->e_ident, ELFMAG, SELFMAG) != 0) {
    why = "not an ELF file";
    return false;
  }
  if (eh->e_ident[EI_CLASS] != ELFCLASS64 || eh->e_ident[EI_DATA] != ELFDATA2LSB ||
      eh->e_machine != kMachine) {
    why = "built for another machine (not a 64-bit little-endian ELF for this one)";
    return false;
  }
  if (eh->e_type != ET_DYN) {
    why = "not a shared library (ELF type is not ET_DYN)";
    return false;
  }
  if (eh->e_shentsize != sizeof(Elf64_Shdr) || eh->e_shnum == 0) {
    why = "has no readable section headers";
    return false;
  }
  const auto section = [&](std::uint64_t i) {
    return r.value<Elf64_Shdr>(eh->e_shoff + i * sizeof(Elf64_Shdr));
  };
  for (std::uint64_t i = 0; i < eh->e_shnum; ++i) {
    const auto sh = section(i);
    if (!sh) {
      why = "section headers lie beyond the end of the file";
      return false;
    }
    if (sh->sh_type != SHT_DYNSYM) continue;
    if (sh->sh_entsize != sizeof(Elf64_Sym) || sh->sh_link >= eh->e_shnum) break;
    const auto strings_header = section(sh->sh_link);
    if (!strings_header) break;
    const auto symbols = r.bytes(sh->sh_offset, sh->sh_size);
    const auto strings = r.bytes(strings_header->sh_offset, strings_header->sh_size);
    if (!symbols || !strings) {
      why = "its dynamic symbol table lies beyond the end of the file";
      return false;
    }
    for (std::uint64_t k = 0; k + sizeof(Elf64_Sym) <= symbols->size(); k += sizeof(Elf64_Sym)) {
      Elf64_Sym s;
      std::memcpy(&s, symbols->data() + k, sizeof(s));
      if (s.st_name >= strings->size() || s.st_shndx == SHN_UNDEF) continue;
      if (ELF64_ST_TYPE(s.st_info) != STT_FUNC) continue;
      const int bind = ELF64_ST_BIND(s.st_info);
      if (bind != STB_GLOBAL && bind != STB_WEAK) continue;
      const char* name = strings->data() + s.st_name;
      const std::size_t room = strings->size() - s.st_name;
      if (symbol.size() < room && std::memcmp(name, symbol.c_str(), symbol.size() + 1) == 0)
        return true;
    }
    break;
  }
  why = "no entry point '" + symbol + "' among its dynamic symbols (is SOMASIM_PLUGIN_LIBRARY " +
        "missing?)";
  return false;
}

}  // namespace somasim
