#include "apps/args.h"

#include <iostream>
#include <sstream>

#include "harness/shards.h"

namespace symembed {

ArgParser::ArgParser(std::string command, std::string summary)
    : command_(std::move(command)), summary_(std::move(summary)) {}

void ArgParser::Option(const std::string& name, const std::string& help,
                       const std::string& default_value) {
  specs_[name] = Spec{help, default_value, false};
  order_.push_back(name);
}

void ArgParser::Switch(const std::string& name, const std::string& help) {
  specs_[name] = Spec{help, "", true};
  order_.push_back(name);
}

void ArgParser::Repeated(const std::string& name, const std::string& help) {
  specs_[name] = Spec{help, "", false, true};
  order_.push_back(name);
}

std::vector<std::string> ArgParser::GetAll(const std::string& name) const {
  auto it = repeated_values_.find(name);
  return it == repeated_values_.end() ? std::vector<std::string>{} : it->second;
}

void ArgParser::Positionals(const std::string& usage, const std::string& help, int min, int max) {
  positional_usage_ = usage;
  positional_help_ = help;
  min_positionals_ = min;
  max_positionals_ = max;
}

bool ArgParser::Parse(const std::vector<std::string>& args) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      std::cout << Help();
      return false;
    }
    if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
      std::string name = a.substr(2), value;
      const size_t eq = name.find('=');
      const bool has_value = eq != std::string::npos;
      if (has_value) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      auto it = specs_.find(name);
      if (it == specs_.end()) throw UsageError{"unknown option --" + name};
      if (it->second.is_switch) {
        if (has_value) throw UsageError{"option --" + name + " takes no value"};
        values_[name] = "1";
      } else {
        if (!has_value) {
          if (i + 1 >= args.size()) throw UsageError{"option --" + name + " needs a value"};
          value = args[++i];
        }
        values_[name] = value;
        if (it->second.repeated) repeated_values_[name].push_back(value);
      }
    } else {
      positionals_.push_back(a);
    }
  }
  const int n = static_cast<int>(positionals_.size());
  if (n < min_positionals_ || (max_positionals_ >= 0 && n > max_positionals_)) {
    throw UsageError{n < min_positionals_ ? "missing argument " + positional_usage_
                                          : "too many arguments"};
  }
  return true;
}

std::string ArgParser::Get(const std::string& name) const {
  auto v = values_.find(name);
  if (v != values_.end()) return v->second;
  auto s = specs_.find(name);
  return s == specs_.end() ? "" : s->second.default_value;
}

bool ArgParser::Given(const std::string& name) const { return values_.count(name) > 0; }

bool ArgParser::Flag(const std::string& name) const { return values_.count(name) > 0; }

int ArgParser::GetInt(const std::string& name) const {
  const std::string v = Get(name);
  try {
    size_t used = 0;
    const int x = std::stoi(v, &used);
    if (used != v.size()) throw std::invalid_argument(v);
    return x;
  } catch (const std::exception&) {
    throw UsageError{"option --" + name + " expects an integer, got '" + v + "'"};
  }
}

double ArgParser::GetDouble(const std::string& name) const {
  const std::string v = Get(name);
  try {
    size_t used = 0;
    const double x = std::stod(v, &used);
    if (used != v.size()) throw std::invalid_argument(v);
    return x;
  } catch (const std::exception&) {
    throw UsageError{"option --" + name + " expects a number, got '" + v + "'"};
  }
}

std::string ArgParser::Help() const {
  std::ostringstream out;
  out << "usage: symembed " << command_ << (order_.empty() ? "" : " [options]")
      << (positional_usage_.empty() ? "" : " " + positional_usage_) << "\n\n"
      << summary_ << "\n";
  if (!positional_help_.empty()) out << "\n  " << positional_usage_ << "\n      " << positional_help_ << "\n";
  if (!order_.empty()) out << "\noptions:\n";
  for (const auto& name : order_) {
    const Spec& s = specs_.at(name);
    out << "  --" << name << (s.is_switch ? "" : " VALUE") << (s.repeated ? " (repeatable)" : "")
        << "\n      " << s.help;
    if (!s.is_switch && !s.default_value.empty()) out << " (default: " << s.default_value << ")";
    out << "\n";
  }
  out << "  --help\n      print this help\n";
  return out.str();
}

std::string CommandLine(const std::string& command, const std::vector<std::string>& args) {
  std::string line = "symembed " + command;
  for (const std::string& a : args) line += " " + ShellQuote(a);
  return line;
}

}  // namespace symembed
