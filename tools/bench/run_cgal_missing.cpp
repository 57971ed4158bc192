// Stand-in for run_cgal.cpp when CGAL was not found at configure time.
#include "method.h"

#include <stdexcept>

namespace bench {

bool cgal_available() { return false; }

MethodRun run_cgal(const Mesh &, const std::vector<RaySet> &) {
    throw std::runtime_error("this ppm-bench was built without CGAL");
}

} // namespace bench
