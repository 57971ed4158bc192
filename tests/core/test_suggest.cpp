// SPDX-License-Identifier: Apache-2.0
// "Did you mean": edit distances worked out by hand, and suggestions only for likely typos.
#include "core/suggest.h"

#include "test_support.h"

using namespace ppm;

namespace {

void edit_distance_counts_edits(void **) {
    assert_int_equal(edit_distance("", ""), 0);
    assert_int_equal(edit_distance("abc", ""), 3);
    assert_int_equal(edit_distance("", "ab"), 2);
    assert_int_equal(edit_distance("kitten", "sitting"), 3);
    assert_int_equal(edit_distance("difuse", "diffuse"), 1);  // insertion
    assert_int_equal(edit_distance("diffsue", "diffuse"), 1); // transposition
    assert_int_equal(edit_distance("alpha", "alpah"), 1);     // transposition at the end
    assert_int_equal(edit_distance("seed", "send"), 1);       // substitution
    assert_int_equal(edit_distance("Diffuse", "diffuse"), 1); // case counts
}

void closest_name_suggests_only_typos(void **) {
    const std::vector<std::string> bsdfs = {"diffuse", "conductor", "dielectric", "plastic"};
    assert_true(closest_name("difuse", bsdfs) == "diffuse");
    assert_true(closest_name("dielectirc", bsdfs) == "dielectric");
    assert_true(closest_name("plastik", bsdfs) == "plastic");
    assert_true(closest_name("roughconductor", bsdfs).empty()); // another name, not a typo
    assert_true(closest_name("x", bsdfs).empty());
    assert_true(did_you_mean("conductr", bsdfs) == " (did you mean 'conductor'?)");
    assert_true(did_you_mean("velvet", bsdfs).empty());
    assert_true(closest_name("anything", {}).empty());
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(edit_distance_counts_edits),
        cmocka_unit_test(closest_name_suggests_only_typos),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
