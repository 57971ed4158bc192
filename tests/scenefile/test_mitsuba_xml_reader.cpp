// SPDX-License-Identifier: Apache-2.0
// Mitsuba XML scene files read into libppm's scene structure: parameters and their
// substitution, includes, references, transforms, the sensor's field of view, the integrator
// and sampler, lenient substitutes, and located errors for malformed or inconsistent files.
#include "core/error.h"
#include "scenefile/mitsuba_xml.h"

#include "test_support.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

using namespace ppm;

namespace {

char folder[4096];

std::string write(const char *name, const std::string &text) {
    const std::string path = std::string(folder) + "/" + name;
    FILE *file = std::fopen(path.c_str(), "wb");
    assert_non_null(file);
    assert_int_equal(std::fwrite(text.data(), 1, text.size(), file), text.size());
    assert_int_equal(std::fclose(file), 0);
    return path;
}

template <class Load> std::string error_of(Load &&load, ppm_status expected = PPM_ERROR_PARSE) {
    try {
        load();
    } catch (const Error &e) {
        assert_int_equal(e.status(), expected);
        return e.what();
    }
    fail_msg("no error thrown");
    return "";
}

void assert_contains(const std::string &text, const char *fragment) {
    if (text.find(fragment) == std::string::npos) fail_msg("'%s' lacks '%s'", text.c_str(), fragment);
}
void assert_contains(const std::string &text, const std::string &fragment) { assert_contains(text, fragment.c_str()); }

const char *kCornell = R"(<scene version="3.0.0">
    <default name="spp" value="16"/>
    <default name="res" value="64"/>
    <integrator type="path">
        <integer name="max_depth" value="8"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <string name="fov_axis" value="y"/>
        <transform name="to_world">
            <lookat origin="0, 1, 6.8" target="0, 1, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="$res"/>
            <integer name="height" value="$res"/>
            <rfilter type="gaussian"/>
        </film>
    </sensor>
    <bsdf type="twosided" id="white">
        <bsdf type="diffuse">
            <rgb name="reflectance" value="0.75, 0.75, 0.75"/>
        </bsdf>
    </bsdf>
    <include filename="shapes.xml"/>
</scene>
)";

const char *kShapes = R"(<scene version="3.0.0">
    <shape type="rectangle">
        <transform name="to_world">
            <scale value="2"/>
            <rotate x="1" angle="-90"/>
            <translate y="2"/>
        </transform>
        <ref id="white"/>
        <emitter type="area">
            <rgb name="radiance" value="10"/>
        </emitter>
    </shape>
    <shape type="sphere">
        <point name="center" x="0" y="0.5" z="0"/>
        <float name="radius" value="0.5"/>
        <bsdf type="dielectric">
            <string name="int_ior" value="bk7"/>
        </bsdf>
    </shape>
</scene>
)";

void a_scene_with_defaults_includes_and_refs_maps_onto_the_json_structure(void **) {
    const std::string path = write("cornell.xml", kCornell);
    write("shapes.xml", kShapes);
    XmlOptions options;
    options.defines["res"] = "32"; // wins over the file's default
    const XmlScene scene = read_mitsuba_xml(path, options);
    const Json::Value &root = scene.root;

    assert_int_equal(root["integrator"]["max_depth"].asInt(), 7); // Mitsuba counts the emitter
    assert_int_equal(root["integrator"]["passes"].asInt(), 16);   // sample_count, from the default
    assert_int_equal(root["sensor"]["film"]["width"].asInt(), 32);
    // fov 40 along y on a square film is 40 along x too.
    assert_close(root["sensor"]["fov"].asDouble(), 40.0, 1e-12);
    assert_close(root["sensor"]["to_world"][0]["look_at"]["origin"][2].asDouble(), 6.8, 0);

    assert_string_equal(root["bsdfs"]["white"]["type"].asCString(), "diffuse"); // twosided unwrapped
    assert_close(root["bsdfs"]["white"]["reflectance"][1].asDouble(), 0.75, 0);

    const Json::Value &shapes = root["shapes"];
    assert_int_equal(shapes.size(), 2);
    assert_string_equal(shapes[0]["bsdf"].asCString(), "white");
    assert_close(shapes[0]["emitter"]["radiance"][2].asDouble(), 10, 0);
    const Json::Value &ops = shapes[0]["to_world"];
    assert_close(ops[0]["scale"].asDouble(), 2, 0);
    assert_close(ops[1]["rotate"]["axis"][0].asDouble(), 1, 0);
    assert_close(ops[1]["rotate"]["angle"].asDouble(), -90, 0);
    assert_close(ops[2]["translate"][1].asDouble(), 2, 0);
    assert_close(shapes[1]["bsdf"]["int_ior"].asDouble(), 1.5046, 0); // Mitsuba's named IOR
    assert_close(shapes[1]["center"][1].asDouble(), 0.5, 0);

    // Every value knows where it came from, also across the include.
    assert_contains(scene.sources.location(static_cast<std::size_t>(shapes[1]["radius"].getOffsetStart())),
                    "shapes.xml:15:9");
    assert_contains(scene.sources.location(static_cast<std::size_t>(root["sensor"]["fov"].getOffsetStart())),
                    "cornell.xml:8:9");

    // What libppm reads differently is said once per element.
    std::string warnings;
    for (const std::string &w : scene.warnings) warnings += w + "\n";
    assert_contains(warnings, "integrator 'path' read as \"render this scene\"");
    // The gaussian pixel filter passes on (a filter with negative lobes would be read as one).
    assert_string_equal(root["sensor"]["film"]["rfilter"]["type"].asCString(), "gaussian");
}

void the_field_of_view_is_converted_to_the_x_axis(void **) {
    struct Case {
        const char *axis;
        double expected_tan_ratio; // tan(fov_x / 2) / tan(fov / 2) on a 200 x 100 film
    } cases[] = {{"x", 1}, {"y", 2}, {"diagonal", 2 / std::sqrt(5.0)}, {"smaller", 2}, {"larger", 1}};
    for (const Case &c : cases) {
        const std::string path =
            write("fov.xml", std::string(R"(<scene version="3.0.0"><sensor type="perspective">)") +
                                 R"(<float name="fov" value="30"/><string name="fov_axis" value=")" + c.axis +
                                 R"("/><film type="hdrfilm"><integer name="width" value="200"/>)" +
                                 R"(<integer name="height" value="100"/></film></sensor></scene>)");
        const XmlScene scene = read_mitsuba_xml(path, {});
        const double fov_x = scene.root["sensor"]["fov"].asDouble();
        assert_close(std::tan(fov_x * M_PI / 360) / std::tan(30 * M_PI / 360), c.expected_tan_ratio, 1e-12);
    }
}

// Reference values printed by Mitsuba 3.9.1 (scalar_rgb) for the same elements, read back with
// mitsuba.traverse: a reflectance is weighed with D65, an emission is not, and a single value
// is grey as a reflectance but equal-energy white as an emission.
void spectra_become_the_rgb_mitsuba_gives_them(void **) {
    const std::string path = write("spectra.xml", R"(<scene version="3.0.0">
    <bsdf type="diffuse" id="measured">
        <spectrum name="reflectance" value="400:0.1, 500:0.5, 600:0.8, 700:0.3"/>
    </bsdf>
    <bsdf type="diffuse" id="flat"><spectrum name="reflectance" value="360:1, 830:1"/></bsdf>
    <bsdf type="diffuse" id="grey"><spectrum name="reflectance" value="0.5"/></bsdf>
    <shape type="sphere">
        <emitter type="area"><spectrum name="radiance" value="400:0.1, 500:0.5, 600:0.8, 700:0.3"/></emitter>
    </shape>
    <shape type="sphere">
        <emitter type="area"><spectrum name="radiance" value="5"/></emitter>
    </shape>
</scene>
)");
    const XmlScene scene = read_mitsuba_xml(path, {});
    const auto assert_rgb = [](const Json::Value &value, double r, double g, double b) {
        assert_close(value[0].asDouble(), r, 2e-6);
        assert_close(value[1].asDouble(), g, 2e-6);
        assert_close(value[2].asDouble(), b, 2e-6);
    };
    assert_rgb(scene.root["bsdfs"]["measured"]["reflectance"], 0.752187, 0.645269, 0.271706);
    assert_rgb(scene.root["bsdfs"]["flat"]["reflectance"], 0.998985, 0.998874, 0.998802);
    assert_rgb(scene.root["bsdfs"]["grey"]["reflectance"], 0.5, 0.5, 0.5);
    assert_rgb(scene.root["shapes"][0]["emitter"]["radiance"], 0.883847, 0.618319, 0.236324);
    assert_close(scene.root["shapes"][1]["emitter"]["radiance"][0].asDouble(), 6.02397, 2e-5);
    assert_close(scene.root["shapes"][1]["emitter"]["radiance"][1].asDouble(), 4.74146, 2e-5);
    assert_close(scene.root["shapes"][1]["emitter"]["radiance"][2].asDouble(), 4.54458, 2e-5);

    // A narrow band outside the sRGB gamut is clamped, with a warning (Mitsuba: 0.00939, 0, 0.2017).
    const std::string narrow = write("narrow.xml", R"(<scene version="3.0.0">
    <bsdf type="diffuse" id="blue"><spectrum name="reflectance" value="450:1, 460:1"/></bsdf>
</scene>
)");
    const XmlScene clamped = read_mitsuba_xml(narrow, {});
    assert_rgb(clamped.root["bsdfs"]["blue"]["reflectance"], 0.00939023, 0, 0.201667);
    assert_int_equal(clamped.warnings.size(), 1);
    assert_contains(clamped.warnings[0], "narrow.xml:2:36: <spectrum>: the spectrum's colour");
    // A conductor's eta and k are unbounded (Mitsuba's get_unbounded_texture): D65-weighted
    // like a reflectance, but not clamped to 1.
    const XmlScene metal = read_mitsuba_xml(write("metal.xml", R"(<scene version="3.0.0">
    <bsdf type="conductor" id="m"><spectrum name="eta" value="360:2, 830:2"/>
        <spectrum name="k" value="360:3.5, 830:3.5"/></bsdf>
</scene>
)"),
                                            {});
    assert_rgb(metal.root["bsdfs"]["m"]["eta"], 2 * 0.998985, 2 * 0.998874, 2 * 0.998802);
    assert_rgb(metal.root["bsdfs"]["m"]["k"], 3.5 * 0.998985, 3.5 * 0.998874, 3.5 * 0.998802);
    assert_int_equal(metal.warnings.size(), 0);
    assert_contains(error_of([&] {
                        read_mitsuba_xml(write("bad.xml", R"(<scene version="3.0.0"><bsdf type="diffuse" id="x">
<spectrum name="reflectance" value="500:0.1, 400:0.2"/></bsdf></scene>)"),
                                         {});
                    }),
                    "bad.xml:2:1: <spectrum>: wavelengths must increase");
}

void lenient_mode_substitutes_with_a_warning_and_strict_mode_names_the_element(void **) {
    const std::string path = write("rough.xml", R"(<scene version="3.0.0">
    <emitter type="sunsky"><string name="filename" value="sky"/></emitter>
    <shape type="sphere">
        <bsdf type="hair"><float name="alpha" value="0.1"/></bsdf>
    </shape>
    <medium type="homogeneous" id="fog"/>
</scene>
)");
    XmlOptions lenient;
    lenient.lenient = true;
    const XmlScene scene = read_mitsuba_xml(path, lenient);
    assert_string_equal(scene.root["shapes"][0]["bsdf"]["type"].asCString(), "diffuse");
    assert_false(scene.root.isMember("emitters"));
    std::string warnings;
    for (const std::string &w : scene.warnings) warnings += w + "\n";
    assert_contains(warnings, "rough.xml:2:5: <emitter>: emitter type 'sunsky' is not supported by libppm: skipped");
    assert_contains(warnings, "rough.xml:4:9: <bsdf>: BSDF type 'hair' is not supported by libppm: diffuse grey");
    // The medium at the top is not used by anything: said, not substituted.
    assert_contains(warnings, "rough.xml:6:5: <medium>: no object refers to this id: it is not used");
    assert_int_equal(scene.substituted_at.size(), 2);

    // Strict: the first unsupported element is the error, with what libppm supports.
    const std::string strict = error_of([&] { read_mitsuba_xml(path, {}); });
    assert_contains(strict, "rough.xml:2:5: <emitter>: emitter type 'sunsky' is not supported by libppm (supported: ");
    assert_contains(strict, "(with --lenient it is skipped with a warning)");
}

// --lenient reaches every level: a texture inside a BSDF inside a blend keeps its parameter's
// default, a bump map leaves the BSDF it wraps (whose named IOR is read), a medium a shape
// refers to is left out; strict reading names each of them at its element.
void lenient_mode_substitutes_at_every_nesting_level(void **) {
    const std::string path = write("nested.xml", R"(<scene version="3.0.0">
    <medium type="homogeneous" id="fog"/>
    <shape type="sphere">
        <bsdf type="blendbsdf">
            <bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"/></bsdf>
            <bsdf type="roughplastic"/>
        </bsdf>
        <ref name="interior" id="fog"/>
    </shape>
    <shape type="sphere">
        <bsdf type="bumpmap">
            <texture type="bitmap" name="arbitrary"><string name="filename" value="bumps.png"/></texture>
            <bsdf type="dielectric"><string name="ext_ior" value="air"/></bsdf>
        </bsdf>
    </shape>
</scene>
)");
    XmlOptions lenient;
    lenient.lenient = true;
    const XmlScene scene = read_mitsuba_xml(path, lenient);
    const Json::Value &blend = scene.root["shapes"][0]["bsdf"];
    assert_string_equal(blend["type"].asCString(), "blendbsdf");
    assert_false(blend["bsdf_0"].isMember("reflectance"));
    assert_false(scene.root["shapes"][0].isMember("interior"));
    const Json::Value &glass = scene.root["shapes"][1]["bsdf"];
    assert_string_equal(glass["type"].asCString(), "dielectric");
    assert_close(glass["ext_ior"].asDouble(), 1.000277, 0);
    std::string warnings;
    for (const std::string &w : scene.warnings) warnings += w + "\n";
    assert_contains(warnings, "nested.xml:5:34: <texture>: texture type 'mesh_attribute' is not supported by libppm");
    assert_contains(warnings, "nested.xml:8:9: <ref>: <medium> is not supported by libppm");
    assert_contains(warnings,
                    "nested.xml:11:9: <bsdf>: BSDF type 'bumpmap' is not supported by libppm: the BSDF it wraps");
    if (scene.substituted_at.size() != 3)
        fail_msg("%zu substitutions:\n%s", scene.substituted_at.size(), warnings.c_str());
    assert_contains(error_of([&] { read_mitsuba_xml(path, {}); }),
                    "nested.xml:5:34: <texture>: texture type 'mesh_attribute' is not supported by libppm");
    const std::string texture_only = write("nested_texture.xml", R"(<scene version="3.0.0"><shape type="sphere">
<bsdf type="blendbsdf"><bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"/></bsdf>
<bsdf type="diffuse"/></bsdf></shape></scene>)");
    assert_contains(error_of([&] { read_mitsuba_xml(texture_only, {}); }),
                    "nested_texture.xml:2:45: <texture>: texture type 'mesh_attribute' is not supported by libppm "
                    "(supported: ");
}

void malformed_or_inconsistent_files_are_located_errors(void **) {
    assert_contains(error_of([&] {
                        read_mitsuba_xml(
                            write("a.xml", "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n</scene>\n"), {});
                    }),
                    "a.xml:3:");
    assert_contains(error_of([&] {
                        read_mitsuba_xml(write("b.xml", "<scene version=\"3.0.0\"><shape type=\"obj\"><string "
                                                        "name=\"filename\" value=\"$mesh\"/></shape></scene>"),
                                         {});
                    }),
                    "the parameter $mesh has no value");
    assert_contains(
        error_of([&] {
            read_mitsuba_xml(
                write("c.xml",
                      "<scene version=\"3.0.0\">\n  <shape type=\"sphere\"><ref id=\"nothing\"/></shape></scene>"),
                {});
        }),
        "c.xml:2:24: <ref>: no object has the id \"nothing\"");
    write("loop1.xml", "<scene version=\"3.0.0\"><include filename=\"loop2.xml\"/></scene>");
    write("loop2.xml", "<scene version=\"3.0.0\">\n<include filename=\"loop1.xml\"/></scene>");
    assert_contains(error_of([&] { read_mitsuba_xml(std::string(folder) + "/loop1.xml", {}); }),
                    "loop2.xml:2:1: <include>: cyclic include");
    const std::string missing = error_of(
        [&] {
            read_mitsuba_xml(write("d.xml", "<scene version=\"3.0.0\"><include filename=\"gone.xml\"/></scene>"), {});
        },
        PPM_ERROR_IO);
    assert_contains(missing, "d.xml:1:24: <include>");
    assert_contains(missing, "gone.xml");
    assert_contains(error_of([&] { read_mitsuba_xml(write("e.xml", "<scene><shape type=\"sphere\"/></scene>"), {}); }),
                    "the 'version' attribute is missing");
    assert_contains(error_of([&] {
                        read_mitsuba_xml(write("f.xml", "<scene version=\"3.0.0\"><shape type=\"sphere\"><float "
                                                        "name=\"radius\" value=\"one\"/></shape></scene>"),
                                         {});
                    }),
                    "'one' is not a finite number");
    assert_contains(error_of([&] {
                        read_mitsuba_xml(write("g.xml",
                                               "<scene version=\"3.0.0\"><shape type=\"sphere\"><transform "
                                               "name=\"to_world\"><shear value=\"1\"/></transform></shape></scene>"),
                                         {});
                    }),
                    "unknown transform operation");
    assert_contains(error_of([&] {
                        read_mitsuba_xml(write("h.xml",
                                               "<scene version=\"3.0.0\"><bsdf type=\"dielectric\" id=\"x\"><string "
                                               "name=\"int_ior\" value=\"unobtainium\"/></bsdf></scene>"),
                                         {});
                    }),
                    "int_ior \"unobtainium\" is not a known material");
    assert_contains(error_of([&] { read_mitsuba_xml(write("i.xml", "<json/>"), {}); }),
                    "the root element must be <scene>");
}

// blendbsdf's nested BSDFs: references in any role become the named material, nested elements
// keep their name as role, unnamed ones are bsdf_0 then bsdf_1 (Mitsuba's order).
void blendbsdf_and_mask_nest_their_bsdfs(void **) {
    const XmlScene scene = read_mitsuba_xml(
        write("blend.xml",
              "<scene version=\"3.0.0\"><bsdf type=\"diffuse\" id=\"red\"/>\n"
              "<shape type=\"sphere\"><bsdf type=\"blendbsdf\"><ref name=\"bsdf_1\" id=\"red\"/>"
              "<bsdf type=\"conductor\" name=\"bsdf_0\"/></bsdf></shape>\n"
              "<shape type=\"sphere\"><bsdf type=\"blendbsdf\"><texture type=\"checkerboard\" name=\"weight\"/>"
              "<bsdf type=\"diffuse\"/><ref id=\"red\"/></bsdf></shape>\n"
              "<shape type=\"sphere\"><bsdf type=\"mask\"><float name=\"opacity\" value=\"0.3\"/>"
              "<bsdf type=\"twosided\"><ref id=\"red\"/></bsdf></bsdf></shape></scene>"),
        {});
    const Json::Value &shapes = scene.root["shapes"];
    assert_int_equal(shapes.size(), 3);
    assert_string_equal(shapes[0]["bsdf"]["type"].asCString(), "blendbsdf");
    assert_string_equal(shapes[0]["bsdf"]["bsdf_1"].asCString(), "red");
    assert_string_equal(shapes[0]["bsdf"]["bsdf_0"]["type"].asCString(), "conductor");
    assert_string_equal(shapes[1]["bsdf"]["weight"]["type"].asCString(), "checkerboard");
    assert_string_equal(shapes[1]["bsdf"]["bsdf_0"]["type"].asCString(), "diffuse");
    assert_string_equal(shapes[1]["bsdf"]["bsdf_1"].asCString(), "red");
    assert_string_equal(shapes[2]["bsdf"]["type"].asCString(), "mask");
    assert_string_equal(shapes[2]["bsdf"]["bsdf"].asCString(), "red"); // twosided unwrapped
}

// Mitsuba's own Cornell box defines its area emitter at the top with an id, after the include
// whose shape refers to it: the shape emits, and the emitter is no light of its own.
void an_area_emitter_at_the_top_is_the_emission_of_the_shapes_that_refer_to_it(void **) {
    write("luminaire.xml", "<scene version=\"3.0.0\"><shape type=\"rectangle\"><ref id=\"lamp\"/></shape></scene>");
    const XmlScene scene =
        read_mitsuba_xml(write("lamp.xml", "<scene version=\"3.0.0\"><include filename=\"luminaire.xml\"/>\n"
                                           "<emitter type=\"area\" id=\"lamp\"><rgb name=\"radiance\" value=\"3\"/>"
                                           "</emitter>\n<emitter type=\"area\" id=\"spare\"/></scene>"),
                         {});
    const Json::Value &root = scene.root;
    assert_int_equal(root["shapes"].size(), 1);
    assert_string_equal(root["shapes"][0]["emitter"]["type"].asCString(), "area");
    assert_close(root["shapes"][0]["emitter"]["radiance"][1].asDouble(), 3, 0);
    assert_false(root.isMember("emitters"));
    // The one no shape refers to is said, at its element.
    assert_int_equal(scene.warnings.size(), 1);
    assert_contains(scene.warnings[0], "lamp.xml:3:1: <emitter>: this area emitter is never used");

    // Without an id it can belong to no shape: an error, or skipped with --lenient.
    const std::string loose = write("loose.xml", "<scene version=\"3.0.0\"><shape type=\"sphere\"/>\n"
                                                 "<emitter type=\"area\"/></scene>");
    assert_contains(error_of([&] { read_mitsuba_xml(loose, {}); }),
                    "loose.xml:2:1: <emitter>: an area emitter at the top has no shape to emit from");
    XmlOptions lenient;
    lenient.lenient = true;
    const XmlScene skipped = read_mitsuba_xml(loose, lenient);
    assert_false(skipped.root.isMember("emitters"));
    assert_int_equal(skipped.warnings.size(), 1);
}

// Mitsuba's file resolver: <path> folders first (the latest first), then the scene's folder;
// an included file's <path> serves its own includes only; the folders are said for a file
// found in none of them.
void path_elements_add_folders_searched_as_mitsuba_searches_them(void **) {
    const std::string root = folder;
    for (const char *sub : {"assets", "later", "fragments", "fragments/more"})
        std::filesystem::create_directories(root + "/paths/" + sub);
    write("paths/assets/mesh.ply", "");
    write("paths/assets/both.ply", "");
    write("paths/later/both.ply", "");
    write("paths/beside.ply", "");
    write("paths/assets/beside.ply", "");
    write("paths/fragments/more/deep.xml", "<scene version=\"3.0.0\"><shape type=\"sphere\"/></scene>");
    write("paths/fragments/part.xml", "<scene version=\"3.0.0\"><path value=\"more\"/><include filename=\"deep.xml\"/>"
                                      "<shape type=\"ply\"><string name=\"filename\" value=\"deep.xml\"/></shape>"
                                      "</scene>");
    const auto shape = [](const char *file) {
        return std::string("<shape type=\"ply\"><string name=\"filename\" value=\"") + file + "\"/></shape>\n";
    };
    const std::string scene_path =
        write("paths/scene.xml", "<scene version=\"3.0.0\">\n<path value=\"assets\"/>\n<path value=\"later\"/>\n" +
                                     shape("mesh.ply") + shape("both.ply") + shape("beside.ply") +
                                     "<include filename=\"fragments/part.xml\"/>\n</scene>");
    const XmlScene scene = read_mitsuba_xml(scene_path, {});
    const Json::Value &shapes = scene.root["shapes"];
    assert_int_equal(shapes.size(), 5);
    assert_string_equal(shapes[0]["filename"].asCString(), (root + "/paths/assets/mesh.ply").c_str());
    assert_string_equal(shapes[1]["filename"].asCString(), (root + "/paths/later/both.ply").c_str());
    assert_string_equal(shapes[2]["filename"].asCString(), (root + "/paths/assets/beside.ply").c_str());
    // The include found deep.xml through its own <path>; the property naming deep.xml did not.
    assert_string_equal(shapes[3]["type"].asCString(), "sphere");
    assert_string_equal(shapes[4]["filename"].asCString(), (root + "/paths/deep.xml").c_str());
    assert_int_equal(scene.warnings.size(), 0);
    assert_int_equal(scene.failure_notes.size(), 1);
    assert_contains(scene.failure_notes[0], "part.xml:1:");
    assert_contains(scene.failure_notes[0], "\"deep.xml\" is in none of the folders searched: " + root +
                                                "/paths/later/, " + root + "/paths/assets/, " + root + "/paths/, " +
                                                root + "/paths/fragments/, ./");

    assert_contains(error_of([&] {
                        read_mitsuba_xml(write("paths/bad.xml", "<scene version=\"3.0.0\">\n <path value=\"nope\"/>"
                                                                "</scene>"),
                                         {});
                    }),
                    "bad.xml:2:2: <path>: the folder \"nope\" does not exist");
    std::filesystem::remove_all(root + "/paths");
}

// Mitsuba gives a lookat without an up vector (or a zero one) the first vector of
// coordinate_system(view direction), so a camera looking straight down y has a frame.
void a_lookat_without_up_gets_mitsubas_frame(void **) {
    const auto up_of = [](const char *lookat) {
        const XmlScene scene = read_mitsuba_xml(write("up.xml", std::string("<scene version=\"3.0.0\"><sensor "
                                                                            "type=\"perspective\"><transform "
                                                                            "name=\"to_world\">") +
                                                                    lookat + "</transform></sensor></scene>"),
                                                {});
        return scene.root["sensor"]["to_world"][0]["look_at"]["up"];
    };
    // Looking along -y: n = (0, -1, 0), sign = 1, a = -1, b = 0, so up = (1, 0, 0).
    Json::Value up = up_of("<lookat origin=\"0, 5, 0\" target=\"0, 0, 0\"/>");
    assert_close(up[0].asDouble(), 1, 0);
    assert_close(up[1].asDouble(), 0, 0);
    assert_close(up[2].asDouble(), 0, 0);
    // n = (0.6, 0, -0.8): sign = -1, a = -1 / (-1.8), b = 0, up = (1 - 0.36 a, 0, 0.6).
    up = up_of("<lookat origin=\"0, 0, 0\" target=\"3, 0, -4\" up=\"0, 0, 0\"/>");
    assert_close(up[0].asDouble(), 1 - 0.36 / 1.8, 1e-15);
    assert_close(up[1].asDouble(), 0, 0);
    assert_close(up[2].asDouble(), 0.6, 1e-15);
    // A given up vector is kept.
    up = up_of("<lookat origin=\"0, 0, 0\" target=\"0, 0, 1\" up=\"0, 2, 0\"/>");
    assert_close(up[1].asDouble(), 2, 0);
}

// Files of Mitsuba 0.x (version < 2.0) are upgraded as Mitsuba 3 upgrades them: camelCase
// names in snake case, diffuse's diffuse_reflectance is its reflectance, uoffset ... vscale
// make to_uv. The upgraded file reads as the same scene written for Mitsuba 3.
void mitsuba_0_6_files_are_upgraded(void **) {
    const char *old_body = R"(
    <integrator type="path"><integer name="maxDepth" value="5"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/><string name="fovAxis" value="y"/><float name="nearClip" value="0.1"/>
        <sampler type="independent"><integer name="sampleCount" value="32"/></sampler>
        <film type="hdrfilm"><integer name="width" value="20"/><integer name="height" value="10"/></film>
    </sensor>
    <shape type="sphere">
        <bsdf type="diffuse">
            <texture type="bitmap" name="diffuseReflectance">
                <string name="filename" value="t.png"/>
                <float name="uoffset" value="0.25"/><float name="uscale" value="2"/>
            </texture>
        </bsdf>
    </shape>
    <shape type="sphere"><bsdf type="dielectric"><float name="intIOR" value="1.33"/></bsdf></shape>
</scene>
)";
    const XmlScene old = read_mitsuba_xml(write("old.xml", std::string("<scene version=\"0.6.0\">") + old_body), {});
    const Json::Value &root = old.root;
    assert_int_equal(root["integrator"]["max_depth"].asInt(), 4);
    assert_int_equal(root["integrator"]["passes"].asInt(), 32);
    assert_close(root["sensor"]["near_clip"].asDouble(), 0.1, 0);
    assert_close(root["sensor"]["fov"].asDouble(), 2 * std::atan(2 * std::tan(M_PI / 8)) * 180 / M_PI, 1e-12);
    const Json::Value &texture = root["shapes"][0]["bsdf"]["reflectance"];
    assert_string_equal(texture["type"].asCString(), "bitmap");
    assert_false(texture.isMember("uoffset") || texture.isMember("uscale"));
    assert_close(texture["to_uv"][0]["translate"][0].asDouble(), 0.25, 0);
    assert_close(texture["to_uv"][1]["scale"][0].asDouble(), 2, 0);
    assert_close(texture["to_uv"][1]["scale"][1].asDouble(), 1, 0);
    assert_close(root["shapes"][1]["bsdf"]["int_ior"].asDouble(), 1.33, 0);
    // A Mitsuba 3 file keeps its names as written (an unknown one is then the builder's error).
    const XmlScene v3 = read_mitsuba_xml(write("new.xml", std::string("<scene version=\"3.0.0\">") + old_body), {});
    assert_true(v3.root["shapes"][1]["bsdf"].isMember("intIOR"));
}

// A sampler (or any object) at the top with an id is read where a <ref> names it, as in
// Mitsuba's documentation scenes; one nothing names is said.
void a_top_level_sampler_is_read_where_it_is_referred_to(void **) {
    const XmlScene scene = read_mitsuba_xml(write("sampler.xml", R"(<scene version="2.1.0">
    <sampler type="independent" id="my_sampler"><integer name="sample_count" value="16"/></sampler>
    <film type="hdrfilm" id="spare"/>
    <sensor type="perspective"><ref id="my_sampler"/></sensor>
    <shape type="sphere"/>
</scene>
)"),
                                            {});
    assert_int_equal(scene.root["integrator"]["passes"].asInt(), 16);
    assert_int_equal(scene.warnings.size(), 1);
    assert_contains(scene.warnings[0], "sampler.xml:3:5: <film>: no object refers to this id");
}

int setup(void **) { return test_make_folder(folder, sizeof folder, "ppm-xml-"); }
int teardown(void **) {
    test_remove_folder(folder);
    return 0;
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_scene_with_defaults_includes_and_refs_maps_onto_the_json_structure),
        cmocka_unit_test(the_field_of_view_is_converted_to_the_x_axis),
        cmocka_unit_test(spectra_become_the_rgb_mitsuba_gives_them),
        cmocka_unit_test(lenient_mode_substitutes_with_a_warning_and_strict_mode_names_the_element),
        cmocka_unit_test(lenient_mode_substitutes_at_every_nesting_level),
        cmocka_unit_test(malformed_or_inconsistent_files_are_located_errors),
        cmocka_unit_test(blendbsdf_and_mask_nest_their_bsdfs),
        cmocka_unit_test(an_area_emitter_at_the_top_is_the_emission_of_the_shapes_that_refer_to_it),
        cmocka_unit_test(path_elements_add_folders_searched_as_mitsuba_searches_them),
        cmocka_unit_test(a_lookat_without_up_gets_mitsubas_frame),
        cmocka_unit_test(mitsuba_0_6_files_are_upgraded),
        cmocka_unit_test(a_top_level_sampler_is_read_where_it_is_referred_to),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
