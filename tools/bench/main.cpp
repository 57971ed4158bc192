// ppm-bench: benchmarks of libppm. Subcommands dispatch to their own files.
#include "intersect_command.h"
#include "render_command.h"
#include "targets_command.h"

#include <ppm/ppm.h>

#include <cstdio>
#include <cstring>

namespace {

void print_usage(std::FILE *out) {
    std::fprintf(out, "usage: ppm-bench <command> [options]\n"
                      "commands:\n"
                      "  intersect   speed against accuracy of patch intersection: libppm, naive Newton,\n"
                      "              Embree and CGAL on tessellations, against a long-double reference\n"
                      "  render      renderer speed: eye pass time, photon paths/s, memory\n"
                      "  targets     the exact intersector's speed and memory targets against Embree and CGAL\n"
                      "              on a uniform mesh, from medians of interleaved timing rounds\n"
                      "options:\n"
                      "  -h, --help  this text ('ppm-bench <command> -h' for a command's options)\n"
                      "  --version   print the libppm version\n");
}

} // namespace

int main(int argc, char **argv) {
    if (argc < 2) {
        print_usage(stderr);
        return 1;
    }
    const char *command = argv[1];
    if (!std::strcmp(command, "-h") || !std::strcmp(command, "--help")) {
        print_usage(stdout);
        return 0;
    }
    if (!std::strcmp(command, "--version")) {
        std::printf("%s\n", ppm_version_string());
        return 0;
    }
    if (!std::strcmp(command, "intersect")) return bench::run_intersect_command(argc, argv, 2);
    if (!std::strcmp(command, "render")) return bench::run_render_command(argc, argv, 2);
    if (!std::strcmp(command, "targets")) return bench::run_targets_command(argc, argv, 2);
    std::fprintf(stderr, "ppm-bench: unknown command '%s'\n", command);
    print_usage(stderr);
    return 1;
}
