// SPDX-License-Identifier: Apache-2.0
// Mitsuba 3 XML scene files (also Mitsuba 2 files, and 0.5 and 0.6 ones, which Mitsuba 3's
// upgrade of names this reader repeats) read into
// libppm's own scene structure (docs/scene-format.md), so that one builder, with its checks and
// messages, serves both formats.
//
// What the reader does with the XML itself: <default> parameters and their $name substitution
// in every attribute (values given by the caller win, as Mitsuba's -D does); <include> of other
// XML files (relative to the including file; a cycle is an error); `id` on any object and
// <ref> to it (a BSDF or texture defined once at the top and used by several shapes);
// <transform> operations in document order; the property elements <float>, <integer>,
// <boolean>, <string>, <rgb>, <spectrum> (a single value: grey), <point>, <vector>.
//
// What it maps (the table in docs/scene-format.md lists every plugin and parameter): sensors
// (fov along the axis `fov_axis` names, converted to libppm's x axis), films, samplers
// (sample_count becomes the number of passes), integrators (any type is read as "render this
// scene" with a warning unless it is sppm or ppm; max_depth converted), BSDFs, emitters and
// shapes, whose types and parameters pass through under their Mitsuba names: the builder
// accepts what libppm renders and names the element of anything else.
//
// Every value carries the position of the XML element it came from, so that an error, also
// one found later by the builder, reads "scene.xml:12:5: shapes[2].bsdf.alpha: ...".
#pragma once

#include "scenefile/source_files.h"

#include <json/value.h>

#include <map>
#include <string>
#include <vector>

namespace ppm {

struct XmlOptions {
    std::map<std::string, std::string> defines; // parameters, overriding the file's <default>s
    bool lenient = false; // substitute what libppm cannot render (with a warning) instead of failing
};

struct XmlScene {
    Json::Value root; // the scene in libppm's structure; offsets are SourceFiles positions
    SourceFiles sources;
    std::vector<std::string> warnings; // "file:line:column: what", one per element
    // Said only if loading then fails, as they may explain the error: files named by the
    // scene that were found in none of the folders searched (an object that names one may
    // still be left out, by --lenient).
    std::vector<std::string> failure_notes;
    std::vector<std::string> substituted_at; // "file:line:column <tag>" of what --lenient replaced or left
                                             // out (each also a warning)
};

// Whether `text` looks like an XML document (its first non-blank character is '<').
bool looks_like_xml(const std::string &text);

// Reads the file `path`, or `text` under the name `path` with its file names relative to
// `folder` ("" or ending in '/'). Throws ppm::Error: IO for a missing or unreadable file
// (the scene or an include), PARSE for malformed XML and everything the reader refuses,
// located as above; the error is a LoadError (scenefile/load_error.h) with the warnings and
// failure notes met before it.
XmlScene read_mitsuba_xml(const std::string &path, const XmlOptions &options);
XmlScene read_mitsuba_xml(const std::string &path, const XmlOptions &options, const std::string *text,
                          const std::string &folder);

} // namespace ppm
