// SPDX-License-Identifier: Apache-2.0
// The mode table: every row has an integrator of its family, the traits agree with each other,
// and names and numbers find their rows.
#include "integrator/photon_integrator.h"
#include "integrator/vcm/vcm_integrator.h"
#include "renderer/integrator_registry.h"
#include "settings/render_modes.h"
#include "settings/render_settings.h"

extern "C" {
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
}

#include <cstring>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

using namespace ppm;

static void every_mode_has_an_integrator_of_its_family(void **) {
    for (const ModeTraits &m : render_modes()) {
        const std::unique_ptr<Integrator> integrator = make_integrator(m.mode);
        assert_non_null(integrator.get());
        const bool photon = dynamic_cast<PhotonIntegrator *>(integrator.get()) != nullptr;
        const bool vcm = dynamic_cast<VcmIntegrator *>(integrator.get()) != nullptr;
        assert_int_equal(photon, m.stores_visible_points);
        assert_int_equal(vcm, m.bidirectional);
    }
}

static void traits_agree_with_each_other(void **) {
    for (const ModeTraits &m : render_modes()) {
        if (m.supports_partials) assert_true(m.pass_independent); // partials merge pass sums
        assert_true(m.bidirectional != m.stores_visible_points);
    }
}

static void names_and_numbers_find_their_rows(void **) {
    std::set<std::string> names;
    std::uint32_t number = 0;
    for (const ModeTraits &m : render_modes()) {
        assert_int_equal(static_cast<std::uint32_t>(m.mode), number++); // file numbers in order
        assert_true(names.insert(m.name).second);
        assert_ptr_equal(find_mode(m.name), &m);
        assert_ptr_equal(find_mode(static_cast<std::uint32_t>(m.mode)), &m);
        assert_ptr_equal(&mode_traits(m.mode), &m);
        assert_string_equal(RenderSettings::mode_name(static_cast<std::uint32_t>(m.mode)), m.name);
        RenderSettings settings;
        settings.set_string("mode", m.name, false);
        assert_true(settings.mode == m.mode);
    }
    assert_null(find_mode(number));
    assert_null(find_mode("spm"));
    assert_string_equal(RenderSettings::mode_name(number), "unknown");
    assert_string_equal(mode_names(&ModeTraits::supports_partials).c_str(), "pppm, vcm, bpt, vm");
    RenderSettings settings;
    try {
        settings.set_string("mode", "spm", false);
        fail_msg("an unknown mode was accepted");
    } catch (const std::exception &e) {
        assert_non_null(std::strstr(e.what(), "mode must be \"sppm\", \"ppm\", \"pppm\", \"vcm\", \"bpt\" or \"vm\""));
        assert_non_null(std::strstr(e.what(), "did you mean"));
    }
}

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_mode_has_an_integrator_of_its_family),
        cmocka_unit_test(traits_agree_with_each_other),
        cmocka_unit_test(names_and_numbers_find_their_rows),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
