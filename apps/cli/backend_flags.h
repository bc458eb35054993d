#pragma once
// The back-end options of every command that renders (render, stream,
// view), on CLI11, filling one BackendOptions (mvr/backends/backend.h).
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mvr/backends/backend.h"

namespace mvr::app {

// One entry of a back end's option table (mvr/option_table.h) as a CLI11
// option bound to its member in `into`; the help gives the range as
// the error names it.
template <class Options>
CLI::Option* addNumber(CLI::App& app, const NumberOption<Options>& n, Options& into) {
  return std::visit(
      [&](auto member) {
        CLI::Option* option =
            app.add_option(n.flag, into.*member, std::string(n.help) + " (must be " + n.range() + ")");
        if (*n.unit) option->type_name(n.unit);
        return option->capture_default_str();
      },
      n.member);
}

// --backend and the options of each back end, bound to one BackendOptions.
// After parsing, resolve() applies --pst to the chosen back end, rejects
// options given for another back end, and validates the values, all before
// any GL or file work.
class BackendFlags {
 public:
  void add(CLI::App& app);
  BackendOptions resolve() const;
  // Where the command line named no accuracy mode (and no texture mode or
  // PST builder, which belong to the GL modes): fastestPst(). Needs a
  // current GL context.
  void chooseDefaultPst(BackendOptions& options, const Scene& scene) const;

 private:
  void copyShared(BackendOptions& o) const;

  BackendOptions options_;
  std::string backend_ = "mvr", acquire_, texture_, builder_, blend_, warpPath_;
  std::optional<std::string> pst_;
  CLI::Option* textureOption_ = nullptr;
  CLI::Option* builderOption_ = nullptr;
  std::vector<CLI::Option*> interpOptions_, warpOptions_;
  CLI::Option* acquireOption_ = nullptr;
};

}  // namespace mvr::app
