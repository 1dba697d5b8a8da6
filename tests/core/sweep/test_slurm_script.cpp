// The sweep's Slurm script with hostile values generated into every field (job name, log
// folder, partition, time, extra options, comments, command words): each value is either
// refused with an InputError or written so that bash, running the script, executes exactly the
// one command with exactly the given words — no injected command runs (marker files), the
// directives stay directives.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "somasim/error.hpp"
#include "somasim/sweep/slurm_script.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {

namespace fs = std::filesystem;
using sweep::SlurmScriptSpec;

// Fragments a careless or hostile value holds: line breaks, command substitutions, quotes,
// separators, comment starts, control and non-ASCII characters.
const std::vector<std::string> kFragments = {"\n",
                                             "\r",
                                             "$(touch m1)",
                                             "`touch m2`",
                                             "; touch m3",
                                             "' ; touch m4 '",
                                             "\"",
                                             "\\",
                                             " ",
                                             "#",
                                             "|touch m5",
                                             "&& touch m6",
                                             "\x7f",
                                             "\t",
                                             "%",
                                             "\xe6\x97\xa5",
                                             "\n#SBATCH --x\ntouch m7\n",
                                             "$HOME",
                                             "${IFS}",
                                             "a",
                                             "debug",
                                             "/tmp/x",
                                             "01:00:00",
                                             "--mem=1G",
                                             "=",
                                             ",",
                                             "'",
                                             "\x01",
                                             ""};

std::vector<std::string> hostile_values(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, kFragments.size() - 1);
  std::uniform_int_distribution<int> count(1, 4);
  std::vector<std::string> out;
  for (int i = 0; i < n; ++i) {
    std::string v;
    for (int k = count(rng); k > 0; --k) v += kFragments[pick(rng)];
    out.push_back(v);
  }
  return out;
}

SlurmScriptSpec plain_spec() {
  SlurmScriptSpec s;
  s.job_name = "sweep";
  s.tasks = 4;
  s.log_dir = "/tmp/logs";
  s.command = {"printf", "%s\\n", "run-one"};
  return s;
}

// Runs `script` with bash in `dir` (task 3); returns its stdout.
std::string run_script(const fs::path& dir, const std::string& script) {
  const fs::path file = dir / "job.sh";
  std::ofstream(file) << script;
  const std::string cmd =
      "cd '" + dir.string() + "' && SLURM_ARRAY_TASK_ID=3 bash job.sh > out.txt 2> err.txt";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << read_file(dir / "err.txt") << script;
  return read_file(dir / "out.txt");
}

// Every line before the exec line is a comment or directive (a quoted word of the command may
// span lines; running the script checks the rest).
void expect_shape(const std::string& script) {
  std::istringstream in(script);
  bool exec_seen = false;
  int line = 0;
  for (std::string l; std::getline(in, l) && !exec_seen; ++line) {
    exec_seen = l.rfind("exec ", 0) == 0;
    if (!exec_seen) {
      EXPECT_TRUE(!l.empty() && l.front() == '#') << "line " << line << ":\n" << script;
    }
  }
  EXPECT_TRUE(exec_seen) << script;
}

}  // namespace

TEST(SlurmScript, PlainValues) {
  SlurmScriptSpec s = plain_spec();
  s.throttle = 2;
  s.partition = "debug";
  s.time = "00:10:00";
  s.extra = {"--mem=1G"};
  s.comments = {"a comment"};
  EXPECT_EQ(sweep::slurm_script(s),
            "#!/bin/bash\n#SBATCH --job-name=sweep\n#SBATCH --array=0-3%2\n#SBATCH "
            "--output=/tmp/logs/%A_%a.out\n#SBATCH --error=/tmp/logs/%A_%a.err\n#SBATCH "
            "--partition=debug\n#SBATCH --time=00:10:00\n#SBATCH --mem=1G\n# a comment\nexec "
            "'printf' '%s\\n' 'run-one' --index \"$SLURM_ARRAY_TASK_ID\"\n");
}

TEST(SlurmScript, HostileValuesAreRefusedOrInert) {
  TempDir dir;
  int refused = 0, written = 0;
  std::uint64_t seed = 1;
  for (const char* field :
       {"job_name", "log_dir", "partition", "time", "extra", "comment", "command"}) {
    for (const std::string& v : hostile_values(seed++, 60)) {
      SlurmScriptSpec s = plain_spec();
      const std::string f = field;
      if (f == "job_name") s.job_name = v;
      if (f == "log_dir") s.log_dir = v;
      if (f == "partition") s.partition = v;
      if (f == "time") s.time = v;
      if (f == "extra") s.extra = {v};
      if (f == "comment") s.comments = {v};
      if (f == "command") s.command.push_back(v);
      std::string script;
      try {
        script = sweep::slurm_script(s);
      } catch (const InputError& e) {
        ++refused;
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        continue;
      }
      ++written;
      expect_shape(script);
      const std::string out = run_script(dir.path(), script);
      std::string expected = "run-one\n";
      if (f == "command") expected += v + "\n";
      expected += "--index\n3\n";
      EXPECT_EQ(out, expected) << field << " " << ::testing::PrintToString(v);
      for (const char* marker : {"m1", "m2", "m3", "m4", "m5", "m6", "m7"})
        EXPECT_FALSE(fs::exists(dir.path() / marker))
            << field << " " << marker << " " << ::testing::PrintToString(v);
    }
  }
  std::printf("slurm script: %d hostile values refused, %d written and inert\n", refused, written);
  EXPECT_GT(refused, 50);
  EXPECT_GT(written, 50);
}

}  // namespace somasim::test
