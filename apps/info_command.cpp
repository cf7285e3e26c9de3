#include <cstdio>

#include "commands.hpp"
#include "thalassa/engine.hpp"
#include "thalassa/version.hpp"

namespace thalassa::cli {

void add_info_command(CLI::App& app, InfoArgs& args) {
  CLI::App* info = app.add_subcommand(
      "info", "Print the GL backend, version, renderer and the capabilities thalassa relies on");
  info->add_option("--backend", args.backend, "egl, osmesa or glfw (default: egl, else osmesa)")
      ->check(CLI::IsMember({"egl", "osmesa", "glfw"}));
}

int run_info(const InfoArgs& args) {
  std::string log;
  ContextOptions options;
  options.visible = false;
  std::unique_ptr<GlContext> context;
  try {
    context = args.backend.empty() ? create_headless_context(options, &log)
                                   : create_context(*parse_backend(args.backend), options);
  } catch (const ContextError& error) {
    print_error(error.what());
    return kExitRuntimeFailure;
  }
  const GlInfo info = query_gl_info();
  std::string compiled;
  for (Backend backend : available_backends())
    compiled += (compiled.empty() ? "" : ", ") + std::string(backend_name(backend));
  std::printf("thalassa %s\n", THALASSA_VERSION_STRING);
  std::printf("backend:       %s\n", std::string(backend_name(context->backend())).c_str());
  std::printf("context:       %s\n", context->description().c_str());
  std::printf("backends:      %s (compiled in)\n", compiled.c_str());
  std::printf("GL version:    %s\n", info.version.c_str());
  std::printf("GLSL version:  %s\n", info.glsl_version.c_str());
  std::printf("GL vendor:     %s\n", info.vendor.c_str());
  std::printf("GL renderer:   %s\n", info.renderer.c_str());
  std::printf("capabilities:\n");
  for (const auto& [name, value] : info.capabilities)
    std::printf("  %-44s %s\n", name.c_str(), value.c_str());
  if (!log.empty()) std::printf("fallbacks:\n  %s", log.c_str());
  if (!info.missing.empty()) {
    print_error("this context lacks capabilities thalassa needs (marked 'no' above)");
    return kExitRuntimeFailure;
  }
  return kExitOk;
}

}  // namespace thalassa::cli
