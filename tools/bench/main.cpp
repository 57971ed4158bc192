// SPDX-License-Identifier: Apache-2.0
// ppm-bench: benchmarks of libppm. Each subcommand has its own files: the command line in
// *_args (or render_command), the run in *_command.
#include "intersect_command.h"
#include "render_command.h"
#include "targets_command.h"

#include "common/command_line.h"

namespace {

const char *const description = "Benchmarks of libppm: the patch intersector against naive methods and triangle-mesh\n"
                                "baselines, and the renderer's speed.";
const char *const footer = "'ppm-bench COMMAND --help' lists a command's options. Progress goes to stderr.\n"
                           "Exit status: 0 ok, 1 usage error, 2 runtime error.";

} // namespace

int main(int argc, char **argv) {
    CLI::App app(description, "ppm-bench");
    ppm_tools::configure(app, footer);
    bench::IntersectOptions intersect;
    bench::RenderOptions render;
    bench::TargetsOptions targets;
    CLI::App *intersect_command = bench::add_intersect_command(app, intersect);
    CLI::App *render_command = bench::add_render_command(app, render);
    CLI::App *targets_command = bench::add_targets_command(app, targets);
    app.require_subcommand(1);
    const int parsed = ppm_tools::parse(app, argc, argv);
    if (parsed >= 0) return parsed;
    try {
        if (intersect_command->parsed()) bench::check_intersect_options(intersect);
        if (targets_command->parsed()) bench::check_targets_options(targets);
    } catch (const ppm_tools::UsageError &e) {
        return ppm_tools::report_usage_error(app, e.what());
    }
    if (intersect_command->parsed()) return bench::run_intersect_command(intersect);
    if (render_command->parsed()) return bench::run_render_command(render);
    return bench::run_targets_command(targets);
}
