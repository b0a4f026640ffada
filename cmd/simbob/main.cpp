// simbob: the command-line driver. Each subcommand lives in its own file (commands.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <functional>

#include "cli.h"
#include "commands.h"
#include "plugins.h"
#include "simbob/registry.h"
#include "version.h"

using namespace simbob::cli;

namespace {

// CLI11 says only "The following argument was not expected: --duraton": name the option of that
// command that was meant. Returns false when no unknown long option is found.
bool reportUnknownOption(CLI::App& app, int argc, char** argv) {
  CLI::App* cmd = &app;
  std::string path = "simbob";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.rfind("--", 0) != 0) {
      for (CLI::App* sub : cmd->get_subcommands({}))
        if (sub->get_name() == arg) {
          cmd = sub;
          path += " " + arg;
          break;
        }
      continue;
    }
    const std::string name = arg.substr(0, arg.find('='));
    if (cmd->get_option_no_throw(name) || app.get_option_no_throw(name)) continue;
    std::vector<std::string> names;
    for (const CLI::Option* o : cmd->get_options())
      for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    const std::string near = simbob::didYouMean(name, names);
    std::fprintf(stderr, "%s: error: unknown option '%s'%s; %s --help lists the options\n", path.c_str(),
                 simbob::quoteInput(name).c_str(), near.empty() ? "" : (" (did you mean '" + near + "'?)").c_str(),
                 path.c_str());
    return true;
  }
  return false;
}

// Names an unknown subcommand instead of CLI11's "A subcommand is required".
int unknownCommand(CLI::App& app, int argc, char** argv) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  if (argc < 2 || argv[1][0] == '-' || std::find(names.begin(), names.end(), argv[1]) != names.end()) return 0;
  std::string near = simbob::didYouMean(argv[1], names);
  std::fprintf(stderr,
               "simbob: error: unknown command '%s'%s; commands: run, check, dump, types, compare, batch, plot, "
               "sweep, render, view, info\n",
               argv[1], near.empty() ? "" : (" (did you mean '" + near + "'?)").c_str());
  return kExitUsage;
}

// An output option given as "" is a mistake, not a request for the default name.
int emptyOutputOption(const Invocation& in) {
  const auto& c = in.cmd;
  for (CLI::App* sub : {c.run, c.compare, c.plot, c.batch, c.check, c.dump, c.render, c.view, c.info})
    for (const char* name : {"--out", "--report", "--log-file", "--out-dir", "--settings", "--record", "--video",
                             "--junit", "--artifacts", "--summary-md"}) {
      CLI::Option* o = sub->get_option_no_throw(name);
      if (!o || o->count() == 0) continue;
      for (const std::string& v : o->results())
        if (int code = checkNotEmpty(name, v, true)) return code;
    }
  return 0;
}

// Global settings, plug-ins (their types resolve like the built-ins) and the log, before any
// scene. The log file is created first: it must not be another output of the command.
int prepare(Invocation& in, simbob::Registry& registry) {
  if (int c = readSettings(in.common)) return c;
  if (int c = loadPlugins(registry, in.common.plugins, in.common.extension_folder)) return c;
  for (const std::string& p : in.common.packages) {  // URDF package folders (docs/urdf.md)
    const size_t eq = p.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == p.size()) {
      g_log.error({simbob::ErrorKind::Usage, {}, "--package " + simbob::quoteInput(p) + ": expected NAME=DIR"});
      return kExitUsage;
    }
    registry.addPackage(p.substr(0, eq), p.substr(eq + 1));
  }
  if (!in.common.log_file.empty()) {
    std::vector<NamedPath> outputs = commandOutputs(in);
    outputs.push_back({"--log-file", in.common.log_file});
    if (int c = checkOutputs(outputs, {})) return c;
  }
  return setupLogging(in.common);
}

}  // namespace

// CLI11 builds its options before the try below; an exception there is a bug worth a crash.
int main(int argc, char** argv) {  // NOLINT(bugprone-exception-escape)
  CLI::App app{"simbob: headless batch simulator for mobile robots (Simulator Bob scenes on ODE)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::function<std::string()>([] {
                         const std::string v = versionText();
                         return v.substr(0, v.size() - 1);  // CLI11 adds the newline
                       }));
  Invocation in;
  defineCommands(app, in);
  if (int c = unknownCommand(app, argc, argv)) return c;
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // An unknown option explains the rest ("--duraton 1" also leaves --duration missing).
    if (!reportUnknownOption(app, argc, argv)) app.exit(e);
    return kExitUsage;
  }
  if (int c = emptyOutputOption(in)) return c;
  // The one registry of component types: built here, passed down (--plugin adds its types to it).
  simbob::Registry registry;
  if (!simbob::registerBuiltins(registry)) {
    for (const std::string& p : registry.problems())
      g_log.error({simbob::ErrorKind::Internal, {}, "internal error: " + p});
    return kExitSoftware;
  }
  in.common.registry = &registry;
  int code = kExitUsage;
  try {
    code = prepare(in, registry);
    if (code == kExitOk) code = dispatch(in, registry);
  } catch (const std::exception& e) {
    g_log.error({simbob::ErrorKind::Internal, {}, std::string("internal error: ") + e.what()});
    code = kExitSoftware;
  }
  // A log that could not be written is an output that failed.
  if (int c = g_log.close(); c != 0 && code == kExitOk) code = c;
  return code;
}
