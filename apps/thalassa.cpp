// thalassa — the command-line program (DESIGN section 5).
#include <cstdio>
#include <exception>

#include "commands.hpp"
#include "thalassa/version.hpp"

int main(int argc, char** argv) {
  using namespace thalassa::cli;
  CLI::App app{"thalassa " THALASSA_VERSION_STRING
               ": renders a planet's ocean and atmosphere, headless or in a window"};
  app.require_subcommand(1);
  app.set_version_flag("--version", THALASSA_VERSION_STRING);
  RenderArgs render_args;
  SkyArgs sky_args;
  FlyArgs fly_args;
  ValidateArgs validate_args;
  InfoArgs info_args;
  SeaArgs sea_args;
#ifdef THALASSA_HAVE_VIEW
  ViewArgs view_args;
#endif
  add_render_command(app, render_args);
  add_sky_command(app, sky_args);
  add_fly_command(app, fly_args);
  add_validate_command(app, validate_args);
  add_info_command(app, info_args);
  add_sea_command(app, sea_args);
#ifdef THALASSA_HAVE_VIEW
  add_view_command(app, view_args);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& success) {
    return app.exit(success);  // --help, --version
  } catch (const CLI::ParseError& error) {
    app.exit(error);  // prints the message
    return kExitInvalidInput;
  }
  try {
    if (app.got_subcommand("render")) return run_render(render_args);
    if (app.got_subcommand("sky")) return run_sky(sky_args);
    if (app.got_subcommand("fly")) return run_fly(fly_args);
    if (app.got_subcommand("validate")) return run_validate(validate_args);
    if (app.got_subcommand("info")) return run_info(info_args);
    if (app.got_subcommand("sea")) return run_sea(sea_args);
#ifdef THALASSA_HAVE_VIEW
    if (app.got_subcommand("view")) return run_view(view_args);
#endif
  } catch (const std::exception& error) {
    print_error(error.what());
    return kExitRuntimeFailure;
  }
  return kExitInvalidInput;
}
