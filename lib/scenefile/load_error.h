// SPDX-License-Identifier: Apache-2.0
// An error met while loading a scene file, carrying the warnings collected before it and the
// notes kept for a failure, so that the caller still shows them: they often explain the error
// (a file found in none of the folders searched, an element read differently than written).
#pragma once

#include "core/error.h"

#include <string>
#include <utility>
#include <vector>

namespace ppm {

class LoadError : public Error {
public:
    LoadError(const Error &error, std::vector<std::string> warnings)
        : Error(error.status(), error.what()), warnings_(std::move(warnings)) {}
    const std::vector<std::string> &warnings() const { return warnings_; }

private:
    std::vector<std::string> warnings_;
};

} // namespace ppm
