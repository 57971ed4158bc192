// SPDX-License-Identifier: Apache-2.0
#include "options.h"

#include "common/command_line.h"

#include <cstdlib>

namespace ppm_render {

namespace {

using ppm_tools::UsageError;

const char *const description =
    "Renders a scene file by progressive photon mapping: libppm's JSON (docs/scene-format.md)\n"
    "or a Mitsuba 3 XML file. The image is rewritten atomically as the render converges, so it\n"
    "can be watched and is never lost.";

const char *const footer = "SIGINT or SIGTERM (Ctrl-C) abandons the running pass, writes the images and a checkpoint\n"
                           "and exits 0; a second one exits at once. The progress bar (pass, photons/s, ETA) goes to\n"
                           "stderr when it is a terminal.\n"
                           "Exit status: 0 done (also when interrupted), 1 usage error (options), 2 runtime error\n"
                           "(a bad or missing scene file, setting or checkpoint, an unwritable image).";

// The raw text of the options whose syntax CLI11 does not know; checked after parsing.
struct RawOptions {
    std::vector<std::string> defines, settings;
    std::string size, crop, pass_range;
};

// "KEY=VALUE" into its two non-empty halves.
std::pair<std::string, std::string> key_value(const std::string &text, const char *option, const char *form) {
    const std::size_t equals = text.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == text.size())
        throw UsageError(std::string(option) + " needs " + form + ", not '" + text + "'");
    return {text.substr(0, equals), text.substr(equals + 1)};
}

std::vector<std::string> split(const std::string &text, char separator) {
    std::vector<std::string> items;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(separator, start);
        items.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
        if (end == std::string::npos) return items;
        start = end + 1;
    }
}

// A whole number in [low, high] from `text`, else a UsageError naming the option.
std::int64_t whole_number(const std::string &text, const std::string &option, std::int64_t low, std::int64_t high) {
    char *end = nullptr;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || value < low || value > high)
        throw UsageError(option + " needs whole numbers in " + std::to_string(low) + " .. " + std::to_string(high) +
                         ", not '" + text + "'");
    return value;
}

// A check whose range the help text states in words already.
CLI::Validator unlisted(CLI::Validator validator) {
    validator.description("");
    return validator;
}

void add_options(CLI::App &app, Options &o, RawOptions &raw) {
    const std::string output = "Output";
    app.add_option("SCENE", o.scene, "the scene file (.json, or .xml for Mitsuba 3)")->required()->type_name("");
    app.add_option("-o,--output", o.outputs,
                   "image to write, repeatable: .exr (linear float\n"
                   "radiance), .png, .jpg, .tif (sRGB 8-bit, see\n"
                   "--exposure); default <scene name>.png here")
        ->allow_extra_args(false)
        ->type_name("PATH")
        ->group(output);
    app.add_option("--exposure", o.exposure, "scales 8-bit images by 2^EV before sRGB (default 0)")
        ->check(unlisted(CLI::Range(-100.0, 100.0)))
        ->type_name("EV")
        ->group(output);
    app.add_option("--layers", o.layers,
                   "extra EXR channels, comma separated: radius (gather\n"
                   "radius in scene units), photons (the photon count N)")
        ->delimiter(',')
        ->check(CLI::IsMember({"radius", "photons"}))
        ->type_name("LIST")
        ->allow_extra_args(false)
        ->group(output);
    app.add_option("--write-interval", o.write_interval,
                   "rewrite the images at most every S seconds (default 1;\n"
                   "0: after every pass); always written at the end")
        ->check(unlisted(CLI::NonNegativeNumber))
        ->type_name("S")
        ->group(output);

    const std::string scene = "Scene (override the file)";
    app.add_option("-D", raw.defines,
                   "a parameter of an XML file (its <default name=...>),\n"
                   "repeatable: -D spp=64 -D res=512")
        ->allow_extra_args(false)
        ->type_name("NAME=VALUE")
        ->group(scene);
    app.add_flag("--lenient", o.lenient,
                 "render what is supported of an XML file, at every\n"
                 "level: unsupported BSDFs and refused parameters make a\n"
                 "grey diffuse material, unsupported textures and media\n"
                 "are left out, unsupported emitters and shapes skipped,\n"
                 "each with a warning and listed again at the end\n"
                 "(default: an error naming the element)")
        ->group(scene);
    app.add_option("--size", raw.size,
                   "image size in pixels, e.g. 640x480 (default the film's);\n"
                   "radii given in pixels follow")
        ->type_name("WxH")
        ->group(scene);
    app.add_option("--crop", raw.crop,
                   "render only pixels x0 .. x1-1, y0 .. y1-1 of the image\n"
                   "(after --size); the output is that window")
        ->type_name("X0,Y0,X1,Y1")
        ->group(scene);

    const std::string rendering = "Rendering (override the file's integrator)";
    app.add_option("--passes", o.passes,
                   "total passes (default: integrator.passes, else 16,\n"
                   "or unlimited with --time)")
        ->check(unlisted(CLI::Range(std::int64_t(1), std::int64_t(1) << 40)))
        ->type_name("N")
        ->group(rendering);
    app.add_option("--photons", o.photons,
                   "photon paths (light subpaths in vcm, bpt, vm) per pass\n(default automatic, from the pixel count)")
        ->check(unlisted(CLI::Range(std::int64_t(1), std::int64_t(1) << 31)))
        ->type_name("N")
        ->group(rendering);
    app.add_option("--time", o.time,
                   "wall-clock budget: no pass starts that would end\n"
                   "after it; a pass running at the deadline is abandoned")
        ->check(unlisted(CLI::NonNegativeNumber))
        ->type_name("SECONDS")
        ->group(rendering);
    app.add_option("--seed", o.seed, "random sequence (same seed and passes: same image)")
        ->check(unlisted(CLI::Range(std::int64_t(0), std::int64_t(1) << 53)))
        ->type_name("N")
        ->group(rendering);
    app.add_option("--threads", o.threads, "worker threads (default: all)")
        ->check(unlisted(CLI::Range(std::int64_t(1), std::int64_t(1024))))
        ->type_name("N")
        ->group(rendering);
    app.add_option("--set", raw.settings,
                   "any renderer setting (mode, alpha, initial_radius,\n"
                   "max_depth, hit_point_search, direct_lighting, ...),\n"
                   "repeatable")
        ->allow_extra_args(false)
        ->type_name("KEY=VALUE")
        ->group(rendering);

    const std::string checkpoints = "Checkpoints";
    app.add_option("--checkpoint", o.checkpoint,
                   "where checkpoints go (default <first output>.ppmckpt);\n"
                   "written on SIGINT/SIGTERM, every --checkpoint-interval,\n"
                   "and at the end when this option is given")
        ->type_name("PATH")
        ->group(checkpoints);
    app.add_option("--checkpoint-interval", o.checkpoint_interval,
                   "seconds between periodic checkpoints (default 300;\n"
                   "0: never)")
        ->check(unlisted(CLI::NonNegativeNumber))
        ->type_name("S")
        ->group(checkpoints);
    app.add_option("--resume", o.resume,
                   "continue a render from its checkpoint: with the same\n"
                   "scene and options, the result equals the uninterrupted\n"
                   "render")
        ->type_name("PATH")
        ->group(checkpoints);

    const std::string farms = "Render farms (passes rendered apart, merged exactly by ppm-merge)";
    app.add_option(
           "--pass-range", raw.pass_range,
           "render passes A .. B-1 of the --passes N in the\n"
           "pass-independent mode (the scene's: vcm by default;\npppm if it names sppm or ppm); needs --partial")
        ->type_name("A:B")
        ->group(farms);
    app.add_option("--partial", o.partial,
                   "save the passes as a partial render (.ppmpart) instead\n"
                   "of an image (images only with -o); it is also the\n"
                   "checkpoint: --resume PATH renders the missing passes")
        ->type_name("PATH")
        ->group(farms);

    app.add_flag("-q,--quiet", o.quiet, "no progress bar, no summary (errors are still printed)");
}

// The options CLI11 took as text, and the rules between options.
void finish(Options &o, const RawOptions &raw, bool checkpoint_given) {
    o.checkpoint_given = checkpoint_given;
    for (const std::string &define : raw.defines) o.defines.push_back(key_value(define, "-D", "NAME=VALUE"));
    for (const std::string &setting : raw.settings) o.settings.push_back(key_value(setting, "--set", "KEY=VALUE"));
    if (!raw.size.empty()) {
        const std::vector<std::string> wh = split(raw.size, 'x');
        if (wh.size() != 2) throw UsageError("--size needs WIDTHxHEIGHT such as 640x480, not '" + raw.size + "'");
        o.width = static_cast<std::uint32_t>(whole_number(wh[0], "--size", 1, std::int64_t(1) << 16));
        o.height = static_cast<std::uint32_t>(whole_number(wh[1], "--size", 1, std::int64_t(1) << 16));
    }
    if (!raw.crop.empty()) {
        const std::vector<std::string> corners = split(raw.crop, ',');
        if (corners.size() != 4) throw UsageError("--crop needs X0,Y0,X1,Y1 such as 0,0,64,48, not '" + raw.crop + "'");
        for (int k = 0; k < 4; ++k)
            o.crop[k] = static_cast<std::uint32_t>(whole_number(corners[k], "--crop", 0, std::int64_t(1) << 16));
        if (o.crop[0] >= o.crop[2] || o.crop[1] >= o.crop[3])
            throw UsageError("--crop " + raw.crop + " is empty: X0 < X1 and Y0 < Y1 are needed");
    }
    if (!raw.pass_range.empty()) {
        const std::size_t colon = raw.pass_range.find(':');
        if (colon == std::string::npos)
            throw UsageError("--pass-range needs A:B (passes A .. B-1), not '" + raw.pass_range + "'");
        o.pass_first = whole_number(raw.pass_range.substr(0, colon), "--pass-range", 0, std::int64_t(1) << 32);
        o.pass_end = whole_number(raw.pass_range.substr(colon + 1), "--pass-range", 1, std::int64_t(1) << 32);
        if (o.pass_first >= o.pass_end)
            throw UsageError("--pass-range " + raw.pass_range + " is empty: A must be below B (passes A .. B-1)");
    }
    if (o.pass_first >= 0 && !o.partial_render())
        throw UsageError("--pass-range needs --partial PATH: the passes are saved as a partial render");
    if (o.pass_first >= 0 && o.passes > 0 && o.pass_end > o.passes)
        throw UsageError("--pass-range " + raw.pass_range + " goes beyond --passes " + std::to_string(o.passes));
    if (o.partial_render()) {
        for (const auto &[key, value] : o.settings)
            if (key == "mode" && value != "pppm" && value != "vcm" && value != "bpt" && value != "vm")
                throw UsageError("--partial renders in a pass-independent mode (pppm, the default, vcm, bpt or vm), "
                                 "not --set mode=" +
                                 value);
        if (o.checkpoint_given)
            throw UsageError("--partial PATH is the checkpoint of a partial render; --checkpoint is not needed");
        o.checkpoint = o.partial;
        return;
    }
    if (o.outputs.empty()) {
        std::string name = o.scene.substr(o.scene.rfind('/') == std::string::npos ? 0 : o.scene.rfind('/') + 1);
        const std::size_t dot = name.rfind('.');
        if (dot != std::string::npos && dot > 0) name.resize(dot);
        o.outputs.push_back(name + ".png");
    }
    if (o.checkpoint.empty()) {
        std::string base = o.outputs.front();
        const std::size_t dot = base.rfind('.');
        if (dot != std::string::npos && dot > 0 && base.find('/', dot) == std::string::npos) base.resize(dot);
        o.checkpoint = base + ".ppmckpt";
    }
}

} // namespace

int parse_options(int argc, char **argv, Options *options) {
    CLI::App app(description, "ppm-render");
    ppm_tools::configure(app, footer);
    Options &o = *options;
    RawOptions raw;
    add_options(app, o, raw);
    if (const int status = ppm_tools::parse(app, argc, argv); status >= 0) return status;
    try {
        finish(o, raw, app.count("--checkpoint") > 0);
    } catch (const UsageError &e) {
        return ppm_tools::report_usage_error(app, e.what());
    }
    return -1;
}

} // namespace ppm_render
