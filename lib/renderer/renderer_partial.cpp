// SPDX-License-Identifier: Apache-2.0
// Renderer's partial renders: the pass sums of a pass-independent render with its identity,
// made, merged, and used as its checkpoints.
#include "renderer/renderer.h"

#include "core/error.h"

namespace ppm {

RenderIdentity Renderer::identity() const {
    RenderIdentity id;
    id.width = static_cast<std::uint32_t>(width()), id.height = static_cast<std::uint32_t>(height());
    id.mode = static_cast<std::uint32_t>(settings_.mode);
    id.direct_lighting = settings_.direct_lighting ? 1 : 0;
    id.seed = settings_.seed;
    id.initial_radius = settings_.initial_radius, id.initial_radius_pixels = settings_.initial_radius_pixels;
    id.alpha = settings_.alpha, id.photons_per_pass = paths_per_pass();
    id.max_depth = static_cast<std::uint32_t>(settings_.max_depth);
    id.glossy_gather_alpha_bits = glossy_gather_alpha_bits(settings_.glossy_gather_alpha);
    id.camera_hash = camera_hash(), id.scene_hash = scene_hash();
    return id;
}

Partial *Renderer::make_partial() const {
    require_mode(&ModeTraits::supports_partials, "a partial render");
    PassSums sums;
    film_.with_sums([&](const PassSums &s) {
        if (s.passes().empty()) fail(PPM_ERROR_INVALID_OPERATION, "a partial render needs a completed pass");
        allocate_or_fail("a partial render of " + film_.description(),
                         std::uint64_t(s.pixel_count()) * sizeof(PassSums::Pixel), [&] { sums = s; });
    });
    return new Partial(identity(), std::move(sums), "this renderer");
}

void Renderer::merge_partial(const Partial &partial) {
    std::unique_lock<std::mutex> one_pass(pass_mutex_, std::try_to_lock);
    if (!one_pass.owns_lock()) fail(PPM_ERROR_INVALID_OPERATION, "a pass of this renderer is running");
    require_mode(&ModeTraits::supports_partials, "merging a partial render");
    const std::string difference = partial.identity().difference(identity());
    if (!difference.empty())
        invalid_argument(partial.origin() + " is a partial of another render than this renderer's: " + difference);
    PassSet held;
    film_.with_sums([&](const PassSums &s) { held = s.passes(); });
    if (const auto overlap = partial.sums().passes().first_overlap(held))
        invalid_argument(partial.origin() + " holds pass " + PassSet::describe(*overlap) +
                         ", which this renderer has rendered already");
    if (!started()) film_.set_pass_independent(true);
    film_.merge_sums(partial.sums());
}

void Renderer::load_partial_checkpoint(const std::string &path, const std::string &bytes) {
    const Owned<Partial> partial(Partial::parse(bytes.data(), bytes.size(), path));
    // The mutex is the caller's (load_checkpoint); merge_partial takes it itself.
    const std::string difference = partial->identity().difference(identity());
    if (!difference.empty()) invalid_argument(path + ": checkpoint of another render: " + difference);
    film_.set_pass_independent(true);
    film_.merge_sums(partial->sums());
}

} // namespace ppm
