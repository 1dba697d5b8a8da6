#pragma once
/// @file
/// Small helpers shared by somasim's YAML readers (experiments, robot descriptions): strict
/// scalar parsing and how a YAML value is shown in error messages.
#include <cstdint>
#include <optional>
#include <string>

namespace YAML {
class Node;
}

namespace somasim {

/// A YAML value as shown in messages: "'abc'" for scalars, "a list", "a map", "nothing".
std::string describe_yaml(const YAML::Node& node);

/// The one YAML document of `text` (YAML::Load would silently drop the documents after a
/// `---` separator). Throws YAML::ParserException for invalid YAML and somasim::InputError
/// "holds N YAML documents (separated by '---'); expected one" for several.
YAML::Node load_one_document(const std::string& text);

/// Strict number parsing of a whole scalar (no trailing text). YAML's .nan/.inf spellings are
/// parsed (callers reject them with a precise message).
std::optional<double> parse_double(const std::string& text);
std::optional<std::int64_t> parse_int(const std::string& text);
/// A seed: decimal digits only (no sign, no exponent), at most 2^64 - 1; nullopt otherwise.
std::optional<std::uint64_t> parse_seed(const std::string& text);
/// What a seed must be, for messages.
inline constexpr const char* kSeedExpectation = "an integer in [0, 18446744073709551615]";

/// `text` with control bytes (other than newlines) shown as \xNN: messages quote input, and
/// input must never drive the terminal.
std::string escape_control_bytes(const std::string& text);
/// true/True/TRUE/false/False/FALSE.
std::optional<bool> parse_bool(const std::string& text);

}  // namespace somasim
