// SPDX-License-Identifier: Apache-2.0
// Stand-in for run_cgal.cpp when CGAL was not found at configure time.
#include "method.h"

#include <stdexcept>

namespace bench {

bool cgal_available() { return false; }

std::unique_ptr<Method> make_cgal_method(std::shared_ptr<const Mesh>) {
    throw std::runtime_error("this ppm-bench was built without CGAL");
}

} // namespace bench
