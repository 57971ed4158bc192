// `ppm-bench render`: photon paths per second, eye-pass time and peak memory of the renderer
// on the benchmark scenes (bench_scenes.h), for each hit-point search structure.
#pragma once

namespace bench {
int run_render_command(int argc, char **argv, int first);
}
