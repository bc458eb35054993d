#include "apps/render/render_command.h"

#include "apps/cli/cli.h"
#include "apps/render/render_flags.h"
#include "apps/render/render_job.h"

namespace mvr::app {

namespace {

int run(int argc, char** argv, RenderCommand command) {
  RenderFlags flags(command);
  CLI::App app(flags.description(), flags.name());
  flags.add(app);
  if (auto exit = parseCommandLine(app, argc - 1, argv + 1)) return *exit;
  RenderJob job = flags.describe(app);
  return runJob(job);
}

}  // namespace

int runRender(int argc, char** argv) { return run(argc, argv, RenderCommand::Render); }
int runStream(int argc, char** argv) { return run(argc, argv, RenderCommand::Stream); }
int runSynthesize(int argc, char** argv) { return run(argc, argv, RenderCommand::Synthesize); }

}  // namespace mvr::app
