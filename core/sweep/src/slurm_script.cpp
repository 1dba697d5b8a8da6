#include "somasim/sweep/slurm_script.hpp"

#include <fmt/format.h>

#include <string_view>

#include "somasim/error.hpp"

namespace somasim::sweep {
namespace {

bool directive_char(char c) {
  if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')) return true;
  return std::string_view("._/%+,:=@~-").find(c) != std::string_view::npos;
}

bool control_char(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 0x20 || u == 0x7f;
}

// A character as the message shows it.
std::string shown(char c) {
  if (control_char(c)) return fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
  return fmt::format("'{}'", c);
}

// What the message shows of a value: control characters escaped.
std::string shown(const std::string& s) {
  std::string out;
  for (char c : s)
    out += control_char(c) ? fmt::format("\\x{:02x}", static_cast<unsigned char>(c))
                           : std::string(1, c);
  return out;
}

std::string directive(std::string_view option, const std::string& value, std::string_view what) {
  if (value.empty())
    throw InputError(fmt::format("{}: empty; expected a value for #SBATCH {}", what, option));
  for (char c : value)
    if (!directive_char(c))
      throw InputError(fmt::format(
          "{} '{}': {} cannot be written into an #SBATCH line safely (letters, digits and "
          "'._/%+,:=@~-' can)",
          what, shown(value), shown(c)));
  return fmt::format("#SBATCH {}={}\n", option, value);
}

}  // namespace

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string slurm_script(const SlurmScriptSpec& spec) {
  if (spec.tasks < 1) throw InputError("slurm script: expected at least one task");
  if (spec.throttle < 0)
    throw InputError(fmt::format("--array-throttle {}: expected an integer >= 1", spec.throttle));
  if (spec.command.empty()) throw InputError("slurm script: no command");
  std::string s = "#!/bin/bash\n";
  s += directive("--job-name", spec.job_name, "the sweep's name");
  s += fmt::format("#SBATCH --array=0-{}{}\n", spec.tasks - 1,
                   spec.throttle > 0 ? fmt::format("%{}", spec.throttle) : "");
  s += directive("--output", spec.log_dir + "/%A_%a.out", "the log folder");
  s += directive("--error", spec.log_dir + "/%A_%a.err", "the log folder");
  if (!spec.partition.empty()) s += directive("--partition", spec.partition, "--partition");
  if (!spec.time.empty()) s += directive("--time", spec.time, "--time");
  for (const std::string& a : spec.extra) {
    bool ok = a.size() > 1 && a.front() == '-';
    for (char c : a) ok = ok && !control_char(c);
    if (!ok)
      throw InputError(fmt::format(
          "--sbatch-arg '{}': expected one sbatch option on one line, e.g. --mem=4G", shown(a)));
    s += fmt::format("#SBATCH {}\n", a);
  }
  for (const std::string& line : spec.comments) {
    std::string text = line;
    for (char& c : text)
      if (control_char(c)) c = '?';
    s += fmt::format("# {}\n", text);
  }
  std::string command = "exec";
  for (const std::string& w : spec.command) command += fmt::format(" {}", shell_quote(w));
  if (spec.pass_task_index) command += " --index \"$SLURM_ARRAY_TASK_ID\"";
  return fmt::format("{}{}\n", s, command);
}

}  // namespace somasim::sweep
