// somasim: run experiment graphs headless. See README.md.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "plugin_pages.hpp"
#include "plugin_template.hpp"
#include "recover.hpp"
#include "robot_commands.hpp"
#include "somasim/error.hpp"
#include "somasim/version.hpp"
#include "somasim/yaml_text.hpp"
#include "sweep_commands.hpp"

using namespace somasim::app;

int main(int argc, char** argv) {
  CLI::App app{
      "somasim — headless robot simulator for embodied-cognition experiments.\n"
      "Exit codes: 0 success, 2 bad input (experiment file, parameters, plugins, usage),\n"
      "3 run failed (outputs flushed, error in metrics.json), 130 interrupted (outputs flushed)."};
  app.set_version_flag("--version", somasim::version_text());
  app.require_subcommand(1);
  CommonOptions common;
  app.add_option("--plugin-path", common.plugin_path,
                 "Directory searched for plugin libraries before $SOMASIM_PLUGIN_PATH and the "
                 "install dir (repeatable)");
  std::vector<std::string> resource_path;
  app.add_option("--resource-path", resource_path,
                 "Directory holding URDF packages (package://NAME/... is DIR/NAME/...), searched "
                 "before $SOMASIM_RESOURCE_PATH and $ROS_PACKAGE_PATH (repeatable)");

  RunArgs run;
  auto* run_cmd = app.add_subcommand("run", "Run an experiment; results go to the run folder");
  run_cmd->add_option("file", run.file, "Experiment YAML")->required();
  run_cmd
      ->add_option("--set", run.sets,
                   "Override a value: path=value, e.g. nodes.pps.params.threshold=0.2 (repeatable)")
      ->allow_extra_args(false);  // one value per --set, so `run --set a=1 FILE` works
  run_cmd->add_option("--seed", run.seed, "Replace the experiment's seed");
  run_cmd->add_option("--out", run.out, "Run folder (default: runs/<experiment name>)");
  run_cmd->add_flag("--overwrite", run.overwrite,
                    "Empty an existing run folder first (without it, one is refused)");
  run_cmd->add_flag("--quiet", run.quiet, "No progress line; only warnings and errors on stderr");
  run_cmd
      ->add_option("--progress-every", run.progress_every_s,
                   "Without a terminal: a progress line in the log every SECONDS of wall time "
                   "(0: none)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            const auto v = somasim::parse_double(text);
            return v && std::isfinite(*v) && (*v == 0 || (*v >= 0.1 && *v <= 1e6))
                       ? ""
                       : "expected 0 (never) or seconds in [0.1, 1e6], got " + text;
          },
          "0 or SECONDS in [0.1, 1e6]"))
      ->capture_default_str();

  std::string validate_file;
  std::vector<std::string> validate_sets;
  auto* validate_cmd = app.add_subcommand("validate", "Check an experiment without running it");
  validate_cmd->add_option("file", validate_file, "Experiment YAML")->required();
  validate_cmd->add_option("--set", validate_sets, "Override a value: path=value (repeatable)")
      ->allow_extra_args(false);

  auto* plugins_cmd = app.add_subcommand("plugins", "List the plugins found on the search path");
  std::string describe_name;
  auto* describe_cmd =
      plugins_cmd->add_subcommand("describe", "Parameters and ports of one plugin");
  describe_cmd->add_option("name", describe_name, "Plugin name")->required();
  std::vector<std::string> index_libraries;
  auto* index_cmd = plugins_cmd->add_subcommand(
      "index", "Write the index file of plugin libraries (<library>.index; the build does this)");
  index_cmd->add_option("libraries", index_libraries, "Plugin library files (.so)")->required();
  std::string reference_dir;
  bool reference_check = false;
  auto* reference_cmd = plugins_cmd->add_subcommand(
      "reference", "Write the plugin reference: one Markdown page per plugin library");
  reference_cmd->add_option("dir", reference_dir, "Folder of the pages (e.g. docs/plugins)")
      ->required();
  reference_cmd->add_flag("--check", reference_check,
                          "Write nothing; exit 1 and name the pages that are not current");

  auto* plugin_cmd = app.add_subcommand("plugin", "Start a plugin of your own");
  plugin_cmd->require_subcommand(1);
  std::string new_plugin_name, new_plugin_dir;
  auto* new_plugin_cmd = plugin_cmd->add_subcommand(
      "new", "Write a plugin folder to start from (CMakeLists.txt, the plugin, a harness test)");
  new_plugin_cmd->add_option("name", new_plugin_name, "Plugin name, e.g. my_filter")->required();
  new_plugin_cmd->add_option("--dir", new_plugin_dir, "Folder to write (default: ./NAME)");

  auto* robot_cmd = app.add_subcommand("robot", "Robot descriptions (YAML or URDF)");
  robot_cmd->require_subcommand(1);
  std::string export_robot, export_out, export_overlay;
  auto* export_cmd = robot_cmd->add_subcommand(
      "export-urdf", "Write a robot as URDF (frames, cameras and skin: a YAML overlay)");
  export_cmd->add_option("robot", export_robot, "Robot description (.yaml or .urdf)")->required();
  export_cmd->add_option("--out", export_out, "URDF file to write (default: stdout)");
  export_cmd->add_option("--overlay", export_overlay,
                         "Also write a YAML overlay extending the URDF with the robot's frames, "
                         "cameras and skin patches");

  std::string mjcf_robot, mjcf_out, mjcf_posture;
  double mjcf_bandwidth = 40.0, mjcf_max_torque = 20.0;
  bool mjcf_no_servos = false;
  auto* mjcf_cmd = robot_cmd->add_subcommand(
      "export-mjcf", "Write a robot as a MuJoCo model (MJCF) with position servos");
  mjcf_cmd->add_option("robot", mjcf_robot, "Robot description (.yaml or .urdf)")->required();
  mjcf_cmd->add_option("--out", mjcf_out, "MJCF file to write (default: stdout)");
  mjcf_cmd->add_option("--posture", mjcf_posture,
                       "Posture the servo gains are tuned at, e.g. 'l_elbow: 60' [deg] "
                       "(default: all joints 0)");
  mjcf_cmd->add_option("--servo-bandwidth", mjcf_bandwidth, "Servo bandwidth [1/s]")
      ->check(CLI::PositiveNumber);
  mjcf_cmd->add_option("--max-torque", mjcf_max_torque, "Servo torque bound [N m]")
      ->check(CLI::PositiveNumber);
  mjcf_cmd->add_flag("--no-servos", mjcf_no_servos, "Write no actuators");

  auto* pps_cmd = app.add_subcommand("pps", "PPS learned-map files");
  pps_cmd->require_subcommand(1);
  std::string convert_in, convert_out;
  auto* convert_cmd = pps_cmd->add_subcommand(
      "convert", "Convert a learned map between somasim JSON and the iCub's taxels2D .ini");
  convert_cmd->add_option("input", convert_in, "Learned map (.json or .ini)")->required();
  convert_cmd->add_option("output", convert_out, "File to write (.json or .ini)")->required();

  std::string recover_dir;
  auto* recover_cmd = app.add_subcommand(
      "recover", "Make a killed run's folder consistent: trim partial CSV rows, status killed");
  recover_cmd->add_option("dir", recover_dir, "Run folder whose metrics.json says running")
      ->required();

  std::string graph_file;
  auto* graph_cmd = app.add_subcommand("graph", "Print an experiment's graph in Graphviz DOT");
  graph_cmd->add_option("file", graph_file, "Experiment YAML")->required();

  SweepCommands sweep(app);  // sweep expand | run | run-one | slurm | collect

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Usage errors are bad input too: the same "error: ..." line as every other.
    std::fprintf(stderr, "error: %s\nRun with --help for more information.\n", e.what());
    return kExitBadInput;
  }
  // The resource path reaches the robot loader, and the runs a sweep starts, by the environment.
  if (!resource_path.empty()) {
    std::string value;
    for (const auto& dir : resource_path)
      value += (value.empty() ? "" : ":") + std::filesystem::absolute(dir).string();
    if (const char* old = std::getenv("SOMASIM_RESOURCE_PATH"); old && *old)
      value += std::string(":") + old;
    ::setenv("SOMASIM_RESOURCE_PATH", value.c_str(), 1);
  }
  // One top-level handler: whatever escapes a command becomes one line and an exit code.
  try {
    if (*run_cmd) return cmd_run(common, run);
    if (*validate_cmd) return cmd_validate(common, validate_file, validate_sets);
    if (*describe_cmd) return cmd_describe(common, describe_name);
    if (*index_cmd) return cmd_index_plugins(index_libraries);
    if (*reference_cmd) {
      somasim::PluginRegistry registry(
          somasim::PluginRegistry::default_search_path(common.plugin_path));
      return cmd_plugin_reference(registry, reference_dir, reference_check);
    }
    if (*plugins_cmd) return cmd_plugins(common);
    if (*graph_cmd) return cmd_graph(common, graph_file);
    if (*new_plugin_cmd) return cmd_plugin_new(new_plugin_name, new_plugin_dir);
    if (*recover_cmd) return cmd_recover(recover_dir);
    if (*convert_cmd) return cmd_pps_convert(convert_in, convert_out);
    if (*export_cmd) return cmd_robot_export_urdf(export_robot, export_out, export_overlay);
    if (*mjcf_cmd)
      return cmd_robot_export_mjcf(
          mjcf_robot, mjcf_out, {mjcf_posture, mjcf_bandwidth, mjcf_max_torque, !mjcf_no_servos});
    if (sweep.selected()) return sweep.dispatch(common);
  } catch (const somasim::InputError& e) {
    std::fprintf(stderr, "error: %s\n", somasim::escape_control_bytes(e.what()).c_str());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", somasim::escape_control_bytes(e.what()).c_str());
    return kExitRunFailed;
  } catch (...) {
    std::fprintf(stderr, "error: unknown exception\n");
    return kExitRunFailed;
  }
  return kExitBadInput;
}
