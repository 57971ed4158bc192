// SPDX-License-Identifier: Apache-2.0
// ppm-render: renders a scene file by progressive photon mapping through libppm's public API,
// rewriting the image atomically as it converges, with checkpoints to stop and resume.
#include <ppm/ppm.h>

#include "common/handle.h"
#include "common/status.h"
#include "image_writer.h"
#include "options.h"
#include "progress.h"
#include "signals.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace ppm_render;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// A failed libppm call (a bad scene, setting or checkpoint, or a failure at run time) and
// every other runtime error end with exit status 2 (STYLE.md: 1 is for usage errors).
using ppm_tools::check;

// --set KEY=VALUE: numbers through set_double (which takes integer keys with whole values),
// anything else as a string; the library checks keys and ranges.
void apply_setting(ppm_renderer renderer, const std::string &key, const std::string &value) {
    char *end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    const bool numeric = end != value.c_str() && *end == '\0';
    if (numeric)
        check(ppm_renderer_set_double(renderer, key.c_str(), number), "--set " + key + "=" + value);
    else
        check(ppm_renderer_set_string(renderer, key.c_str(), value.c_str()), "--set " + key + "=" + value);
}

// The scene file with the command line's XML parameters and leniency.
void load_scene_file(ppm_context context, const Options &options, ppm_scene_file *out_file) {
    std::vector<const char *> names, values;
    for (const auto &[name, value] : options.defines) {
        names.push_back(name.c_str());
        values.push_back(value.c_str());
    }
    ppm_scene_file_options load_options;
    ppm_scene_file_options_init(&load_options);
    load_options.define_names = names.data();
    load_options.define_values = values.data();
    load_options.define_count = names.size();
    load_options.lenient = options.lenient ? 1 : 0;
    const ppm_status status = ppm_scene_file_load_v2(context, options.scene.c_str(), &load_options, out_file);
    check(status);
}

// A renderer of the file's camera, resized (--size) and cropped (--crop) as asked.
void create_renderer(ppm_scene_file file, const Options &options, ppm_renderer *out_renderer) {
    ppm_camera_v2 camera;
    ppm_camera_v2_init(&camera);
    check(ppm_scene_file_get_camera_v2(file, &camera), options.scene);
    if (options.width > 0) {
        camera.width = options.width;
        camera.height = options.height;
    }
    if (options.cropped()) {
        if (options.crop[2] > camera.width || options.crop[3] > camera.height)
            throw std::runtime_error("--crop " + std::to_string(options.crop[0]) + "," +
                                     std::to_string(options.crop[1]) + "," + std::to_string(options.crop[2]) + "," +
                                     std::to_string(options.crop[3]) + " reaches beyond the image of " +
                                     std::to_string(camera.width) + " x " + std::to_string(camera.height) + " pixels");
        camera.crop_x0 = options.crop[0];
        camera.crop_y0 = options.crop[1];
        camera.crop_x1 = options.crop[2];
        camera.crop_y1 = options.crop[3];
    }
    check(ppm_scene_file_create_renderer_v2(file, &camera, out_renderer), options.scene);
}

Image read_image(ppm_renderer renderer, const Options &options) {
    int64_t width = 0, height = 0;
    check(ppm_renderer_get_int(renderer, "width", &width));
    check(ppm_renderer_get_int(renderer, "height", &height));
    Image image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    try {
        image.radiance.resize(pixels * 3);
        for (const std::string &name : options.layers) image.layers.push_back(Layer{name, std::vector<float>(pixels)});
    } catch (const std::bad_alloc &) {
        const std::size_t floats = pixels * (3 + options.layers.size());
        throw std::runtime_error("out of memory for the image of " + std::to_string(width) + " x " +
                                 std::to_string(height) + " pixels: " + std::to_string(floats * sizeof(float)) +
                                 " bytes");
    }
    check(ppm_renderer_get_layer(renderer, "radiance", image.radiance.data(), image.radiance.size()));
    for (Layer &layer : image.layers)
        check(ppm_renderer_get_layer(renderer, layer.name.c_str(), layer.data.data(), layer.data.size()));
    return image;
}

void write_images(ppm_renderer renderer, const Options &options) {
    if (options.outputs.empty()) return; // a partial render without -o
    const Image image = read_image(renderer, options);
    for (const std::string &path : options.outputs) write_image_atomically(path, image, options.exposure);
}

std::string joined_outputs(const Options &options) {
    std::string text;
    if (options.partial_render()) text = "partial " + options.partial;
    for (const std::string &path : options.outputs) text += (text.empty() ? "" : ", ") + path;
    return text;
}

// The passes of a partial render: those of its range that the renderer does not hold yet
// (all of them, unless it resumed from the partial).
std::vector<uint64_t> passes_to_render(ppm_renderer renderer, uint64_t first, uint64_t end) {
    std::vector<uint64_t> held;
    int64_t passes = 0;
    check(ppm_renderer_get_int(renderer, "passes", &passes));
    if (passes > 0) {
        ppm_tools::Partial partial;
        check(ppm_renderer_get_partial(renderer, partial.out()));
        size_t count = 0;
        check(ppm_partial_get_passes(partial, nullptr, 0, &count));
        held.resize(2 * count);
        check(ppm_partial_get_passes(partial, held.data(), held.size(), &count));
    }
    std::vector<uint64_t> todo;
    for (uint64_t pass = first; pass < end; ++pass) {
        bool done = false;
        for (size_t k = 0; k + 1 < held.size() && !done; k += 2) done = held[k] <= pass && pass < held[k + 1];
        if (!done) todo.push_back(pass);
    }
    return todo;
}

// A partial render's state, or the checkpoint: written atomically, the render's planned pass
// count recorded in the partial so that ppm-merge can name missing passes.
void save_state(ppm_renderer renderer, const Options &options, uint64_t pass_total) {
    if (!options.partial_render()) {
        check(ppm_renderer_save_checkpoint(renderer, options.checkpoint.c_str()), "checkpoint");
        return;
    }
    int64_t passes = 0;
    check(ppm_renderer_get_int(renderer, "passes", &passes));
    if (passes == 0) return; // nothing to save yet
    ppm_tools::Partial partial;
    check(ppm_renderer_get_partial(renderer, partial.out()), "partial");
    check(ppm_partial_set_int(partial, "pass_total", static_cast<int64_t>(pass_total)), "--partial");
    check(ppm_partial_save(partial, options.partial.c_str()), "--partial");
}

// Cancels the renderer when the time budget runs out, unless stopped first.
class Deadline {
public:
    Deadline(ppm_renderer renderer, double seconds) {
        if (seconds <= 0) return;
        thread_ = std::thread([this, renderer, seconds] {
            std::unique_lock<std::mutex> lock(mutex_);
            if (!wake_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return stop_; })) {
                expired_ = true;
                ppm_renderer_cancel(renderer);
            }
        });
    }
    ~Deadline() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        if (thread_.joinable()) thread_.join();
    }
    bool expired() {
        std::lock_guard<std::mutex> lock(mutex_);
        return expired_;
    }

private:
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false, expired_ = false;
    std::thread thread_;
};

int render(const Options &options, SignalWatcher &signals) {
    ppm_tools::Context context;
    ppm_tools::SceneFile file;
    ppm_tools::Renderer renderer;
    check(ppm_context_create(context.out()), "creating the context");
    if (options.threads > 0) check(ppm_context_set_int(context, "threads", options.threads), "--threads");
    load_scene_file(context, options, file.out());
    create_renderer(file, options, renderer.out());
    // Partial renders are pass-independent: pppm unless the scene names another such mode
    // (--set mode=... is applied below).
    if (options.partial_render()) {
        char mode[16] = "";
        check(ppm_renderer_get_string(renderer, "mode", mode, sizeof mode, nullptr), "--partial");
        const std::string scene_mode = mode;
        if (scene_mode != "vcm" && scene_mode != "bpt" && scene_mode != "vm")
            check(ppm_renderer_set_string(renderer, "mode", "pppm"), "--partial");
    }
    if (options.photons > 0) check(ppm_renderer_set_int(renderer, "photons_per_pass", options.photons), "--photons");
    if (options.seed >= 0) check(ppm_renderer_set_int(renderer, "seed", options.seed), "--seed");
    for (const auto &[key, value] : options.settings) apply_setting(renderer, key, value);

    int64_t file_passes = 0;
    double file_time = 0;
    check(ppm_scene_file_get_int(file, "passes", &file_passes));
    check(ppm_scene_file_get_double(file, "time", &file_time));
    const double budget = options.time >= 0 ? options.time : file_time;
    const uint64_t target = options.passes > 0 ? static_cast<uint64_t>(options.passes)
                            : file_passes > 0  ? static_cast<uint64_t>(file_passes)
                            : budget > 0       ? 0 // until the time is up
                                               : 16;

    if (options.partial_render() && target == 0)
        throw std::runtime_error("--partial needs a pass count (--passes N, or integrator.passes in the scene)");
    if (options.pass_end > 0 && static_cast<uint64_t>(options.pass_end) > target)
        throw std::runtime_error("--pass-range ends at pass " + std::to_string(options.pass_end - 1) + ", beyond the " +
                                 std::to_string(target) + " passes of the render");
    const uint64_t range_first = options.pass_first >= 0 ? static_cast<uint64_t>(options.pass_first) : 0;
    const uint64_t range_end = options.pass_end > 0 ? static_cast<uint64_t>(options.pass_end) : target;

    if (!options.resume.empty()) check(ppm_renderer_load_checkpoint(renderer, options.resume.c_str()), "--resume");
    std::vector<uint64_t> todo;
    if (options.partial_render()) todo = passes_to_render(renderer, range_first, range_end);
    int64_t passes = 0, width = 0, height = 0, paths_per_pass = 0, threads = 0;
    check(ppm_renderer_get_int(renderer, "passes", &passes));
    check(ppm_renderer_get_int(renderer, "width", &width));
    check(ppm_renderer_get_int(renderer, "height", &height));
    check(ppm_renderer_get_int(renderer, "paths_per_pass", &paths_per_pass)); // photons_per_pass, resolved
    check(ppm_context_get_int(context, "threads", &threads));
    if (threads == 0) threads = std::thread::hardware_concurrency(); // 0: all of them
    char mode[16] = "";
    check(ppm_renderer_get_string(renderer, "mode", mode, sizeof mode, nullptr));
    if (!options.quiet) {
        std::fprintf(stderr, "ppm-render: %s: %lld x %lld", options.scene.c_str(), static_cast<long long>(width),
                     static_cast<long long>(height));
        if (options.cropped())
            std::fprintf(stderr, " (crop %u,%u,%u,%u)", options.crop[0], options.crop[1], options.crop[2],
                         options.crop[3]);
        const std::string bidirectional_modes[] = {"vcm", "bpt", "vm"};
        const bool bidirectional = std::find(std::begin(bidirectional_modes), std::end(bidirectional_modes), mode) !=
                                   std::end(bidirectional_modes);
        std::fprintf(stderr, ", %s, %lld %s/pass, ", mode, static_cast<long long>(paths_per_pass),
                     bidirectional ? "light subpaths" : "photons");
        if (options.partial_render()) {
            std::fprintf(stderr, "passes %llu-%llu of %llu (%zu to render) -> partial %s",
                         static_cast<unsigned long long>(range_first), static_cast<unsigned long long>(range_end - 1),
                         static_cast<unsigned long long>(target), todo.size(), options.partial.c_str());
            if (budget > 0) std::fprintf(stderr, ", or %.1f s, whichever ends first", budget);
        } else if (target > 0 && budget > 0)
            std::fprintf(stderr, "%llu passes or %.1f s, whichever ends first", static_cast<unsigned long long>(target),
                         budget);
        else if (target > 0)
            std::fprintf(stderr, "%llu passes", static_cast<unsigned long long>(target));
        else
            std::fprintf(stderr, "passes until %.1f s", budget);
        if (passes > 0) std::fprintf(stderr, " (resuming with %lld passes done)", static_cast<long long>(passes));
        std::fprintf(stderr, ", %lld threads\n", static_cast<long long>(threads));
    }

    int64_t lights = 0;
    check(ppm_renderer_get_int(renderer, "lights", &lights));
    if (lights == 0)
        std::fprintf(stderr,
                     "ppm-render: warning: %s has no light source (no emitter, no shape with an "
                     "emitter): the image will be black\n",
                     options.scene.c_str());

    signals.start([r = renderer.get()] { ppm_renderer_cancel(r); });
    const Clock::time_point start = Clock::now();
    Deadline deadline(renderer, budget);
    ProgressBar progress(!options.quiet);
    Clock::time_point last_write = start, last_checkpoint = start;
    const int64_t first_pass = passes;
    double last_pass_seconds = 0;
    bool stopped_early = false;

    std::size_t next_todo = 0;
    const bool partial = options.partial_render();
    // The progress bar counts the passes of this run's range for a partial render.
    const uint64_t shown_target = partial ? todo.size() + static_cast<uint64_t>(passes) : target;
    while (partial ? next_todo < todo.size() : target == 0 || static_cast<uint64_t>(passes) < target) {
        // No pass starts that would, at the last pass's pace, end after the budget.
        if (budget > 0 && passes > first_pass && seconds_since(start) + last_pass_seconds > budget) break;
        const Clock::time_point pass_start = Clock::now();
        const ppm_status status =
            partial ? ppm_renderer_render_pass_index(renderer, todo[next_todo]) : ppm_renderer_render_pass(renderer);
        if (status == PPM_ERROR_CANCELLED) {
            stopped_early = true;
            break;
        }
        if (status != PPM_OK) {
            progress.finish();
            std::string message = "pass " + std::to_string(passes + 1) + ": " + ppm_last_error_message();
            // The completed passes' image is still written; failing to write it must not hide
            // why the pass failed (out of memory, typically, when the image cannot be read).
            try {
                write_images(renderer, options);
            } catch (const std::exception &e) {
                message += "; then " + std::string(e.what());
            }
            throw std::runtime_error(message);
        }
        last_pass_seconds = seconds_since(pass_start);
        ++passes;
        ++next_todo;

        double photon_seconds = 0;
        check(ppm_renderer_get_double(renderer, "last_photon_pass_seconds", &photon_seconds));
        const double elapsed = seconds_since(start);
        const double per_pass = elapsed / static_cast<double>(passes - first_pass);
        double eta =
            shown_target > 0 ? per_pass * static_cast<double>(shown_target - static_cast<uint64_t>(passes)) : -1;
        if (budget > 0) eta = eta < 0 ? budget - elapsed : std::min(eta, budget - elapsed);
        progress.update(static_cast<uint64_t>(passes), shown_target,
                        photon_seconds > 0 ? static_cast<double>(paths_per_pass) / photon_seconds : 0, elapsed, eta);

        if (seconds_since(last_write) >= options.write_interval) {
            write_images(renderer, options);
            last_write = Clock::now();
        }
        if (options.checkpoint_interval > 0 && seconds_since(last_checkpoint) >= options.checkpoint_interval) {
            save_state(renderer, options, target);
            last_checkpoint = Clock::now();
        }
    }
    progress.finish();
    const double elapsed = seconds_since(start);
    write_images(renderer, options);

    const bool interrupted = signals.interrupted();
    const bool timed_out = stopped_early && !interrupted && deadline.expired();
    if (interrupted || options.checkpoint_given || partial) save_state(renderer, options, target);
    if (!options.quiet) {
        int64_t emitted = 0;
        check(ppm_renderer_get_int(renderer, "photons_emitted", &emitted));
        const int64_t done = passes - first_pass;
        std::fprintf(stderr,
                     "ppm-render: %lld passes (%.1f M photons emitted in all) in %.1f s, %.3f s per pass -> %s\n",
                     static_cast<long long>(passes), static_cast<double>(emitted) / 1e6, elapsed,
                     done > 0 ? elapsed / static_cast<double>(done) : 0.0, joined_outputs(options).c_str());
        if (interrupted)
            std::fprintf(stderr, "ppm-render: interrupted (signal %d); checkpoint %s (continue with --resume %s)\n",
                         signals.signal_number(), options.checkpoint.c_str(), options.checkpoint.c_str());
        else if (timed_out)
            std::fprintf(stderr, "ppm-render: time budget of %.1f s reached during a pass; that pass was abandoned\n",
                         budget);
        else if (options.checkpoint_given)
            std::fprintf(stderr, "ppm-render: checkpoint %s\n", options.checkpoint.c_str());
        if (partial && next_todo < todo.size())
            std::fprintf(stderr, "ppm-render: %zu passes of the range are not rendered; go on with --resume %s\n",
                         todo.size() - next_todo, options.partial.c_str());
        if (passes == 0) std::fprintf(stderr, "ppm-render: warning: no pass completed; the image is black\n");
    }
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    Options options;
    if (const int status = parse_options(argc, argv, &options); status >= 0) return status;
    // Before any work: an output the render could not write is found now, not after it.
    // A format libppm cannot write is a usage error; a missing or read-only folder a runtime one.
    for (const std::string &path : options.outputs) {
        const ppm_status status = ppm_image_check_path(path.c_str());
        if (status != PPM_OK) {
            std::fprintf(stderr, "ppm-render: -o %s\n", ppm_last_error_message());
            return status == PPM_ERROR_INVALID_ARGUMENT ? 1 : 2;
        }
    }
    SignalWatcher signals; // before libppm creates threads: they inherit the blocked signals
    try {
        return render(options, signals);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-render: %s\n", e.what());
        return 2;
    }
}
