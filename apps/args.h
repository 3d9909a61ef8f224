// Command-line parsing for the symembed subcommands: `--name value`, `--name=value`, boolean
// `--flag`, and positionals. Unknown flags and missing values are usage errors (exit 2).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace symembed {

struct UsageError {
  std::string message;
};

class ArgParser {
 public:
  ArgParser(std::string command, std::string summary);

  // Declares a flag taking a value (default shown in --help) or a boolean switch.
  void Option(const std::string& name, const std::string& help, const std::string& default_value);
  void Switch(const std::string& name, const std::string& help);
  // A flag that may be given several times; all values are kept in order.
  void Repeated(const std::string& name, const std::string& help);
  std::vector<std::string> GetAll(const std::string& name) const;
  // Declares the positionals: their usage text and minimum/maximum count (-1: unbounded).
  void Positionals(const std::string& usage, const std::string& help, int min, int max);

  // Parses args (without the subcommand). Returns false when --help was given (help printed).
  // Throws UsageError.
  bool Parse(const std::vector<std::string>& args);

  std::string Get(const std::string& name) const;
  bool Given(const std::string& name) const;
  bool Flag(const std::string& name) const;
  int GetInt(const std::string& name) const;
  double GetDouble(const std::string& name) const;
  const std::vector<std::string>& positionals() const { return positionals_; }
  std::string Help() const;

 private:
  struct Spec {
    std::string help;
    std::string default_value;
    bool is_switch = false;
    bool repeated = false;
  };
  std::map<std::string, std::vector<std::string>> repeated_values_;
  std::string command_, summary_;
  std::map<std::string, Spec> specs_;
  std::vector<std::string> order_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positionals_;
  std::string positional_usage_, positional_help_;
  int min_positionals_ = 0, max_positionals_ = 0;
};

// "symembed COMMAND ARG..." with each argument shell-quoted (for messages: who holds a folder).
std::string CommandLine(const std::string& command, const std::vector<std::string>& args);

}  // namespace symembed
