#include "app/command_line.h"

#include <algorithm>
#include <iostream>

#include "math/edit_distance.h"

namespace lantern::cli {

namespace {

// Every long and short flag of app, with its dashes.
std::vector<std::string> flag_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    for (const std::string& n : o->get_snames()) names.push_back("-" + n);
  }
  return names;
}

// The subcommand being parsed when the error came (the deepest one that
// was named), or app itself.
const CLI::App& active(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands())
    if (sub->parsed()) return active(*sub);
  return app;
}

void suggest(const CLI::App& app, int argc, char** argv) {
  const CLI::App& at = active(app);
  if (&at == &app && argc > 1 && argv[1][0] != '-') {  // an unknown subcommand
    std::vector<std::string> subs;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) subs.push_back(sub->get_name());
    const std::string near = closest(argv[1], subs);
    if (!near.empty()) std::cerr << "\"" << argv[1] << "\" is not a command; did you mean \"" << near << "\"?\n";
    return;
  }
  const std::vector<std::string> flags = flag_names(at);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() < 2 || arg[0] != '-' || (arg[1] >= '0' && arg[1] <= '9')) continue;
    const std::string flag = arg.substr(0, arg.find('='));
    if (std::find(flags.begin(), flags.end(), flag) != flags.end()) continue;
    const std::string near = closest(flag, flags);
    if (!near.empty()) std::cerr << "unknown option \"" << flag << "\"; did you mean \"" << near << "\"?\n";
  }
}

}  // namespace

std::string closest(const std::string& word, const std::vector<std::string>& candidates) {
  return nearest_word(word, candidates, std::max<size_t>(2, word.size() / 3));
}

int parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    return -1;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // CLI11's message
    suggest(app, argc, argv);
    return 2;
  }
}

}  // namespace lantern::cli
