// SPDX-License-Identifier: Apache-2.0
#include "patch_topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace bench {

namespace {

using ref::real;
using Point = std::array<real, 3>;
using EdgeKey = std::array<Point, 4>;

Point point_of(const ref::Patch &patch, int index) { return {patch.p[index][0], patch.p[index][1], patch.p[index][2]}; }

int edge_index(int e, int k) { return e == 0 ? k : e == 1 ? 12 + k : e == 2 ? 4 * k : 4 * k + 3; }

EdgeKey edge_points(const ref::Patch &patch, int e) {
    EdgeKey key;
    for (int k = 0; k < 4; ++k) key[k] = point_of(patch, edge_index(e, k));
    return key;
}

bool collapsed(const EdgeKey &edge) { return edge[0] == edge[1] && edge[1] == edge[2] && edge[2] == edge[3]; }

} // namespace

void edge_parameter(int e, real s, real &u, real &v) {
    u = e == 2 ? 0 : e == 3 ? 1 : s;
    v = e == 0 ? 0 : e == 1 ? 1 : s;
}

std::vector<Seam> find_seams(const std::vector<ref::Patch> &patches) {
    struct Entry {
        int patch, edge;
        bool reversed;
    };
    // Keyed by the edge's points in the direction that compares smaller, so both directions
    // of the same edge meet.
    std::map<EdgeKey, std::vector<Entry>> edges;
    for (int p = 0; p < int(patches.size()); ++p)
        for (int e = 0; e < 4; ++e) {
            EdgeKey key = edge_points(patches[p], e);
            if (collapsed(key)) continue;
            EdgeKey backward{key[3], key[2], key[1], key[0]};
            const bool reversed = backward < key;
            edges[reversed ? backward : key].push_back({p, e, reversed});
        }
    std::vector<Seam> seams;
    for (const auto &entry : edges) {
        const std::vector<Entry> &list = entry.second;
        for (size_t a = 0; a < list.size(); ++a)
            for (size_t b = a + 1; b < list.size(); ++b)
                seams.push_back(
                    {list[a].patch, list[a].edge, list[b].patch, list[b].edge, list[a].reversed != list[b].reversed});
    }
    return seams;
}

std::vector<Corner> find_corners(const std::vector<ref::Patch> &patches, int min_patches) {
    std::map<Point, std::vector<std::pair<int, int>>> at; // point -> (patch, corner index)
    for (int p = 0; p < int(patches.size()); ++p) {
        std::vector<Point> seen;
        for (int k : {0, 3, 12, 15}) {
            const Point q = point_of(patches[p], k);
            if (std::find(seen.begin(), seen.end(), q) != seen.end()) continue; // collapsed edge
            seen.push_back(q);
            at[q].emplace_back(p, k);
        }
    }
    std::vector<Corner> corners;
    for (const auto &entry : at) {
        if (int(entry.second.size()) < min_patches) continue;
        Corner c{};
        for (int k = 0; k < 3; ++k) c.point[k] = entry.first[k];
        c.patches = int(entry.second.size());
        real mean[3] = {0, 0, 0};
        for (const auto &pk : entry.second) {
            const real u = (pk.second == 3 || pk.second == 15) ? 1 : 0, v = pk.second >= 12 ? 1 : 0;
            real s[3], su[3], sv[3];
            ref::evaluate(patches[pk.first], u, v, s, su, sv);
            real n[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2], su[0] * sv[1] - su[1] * sv[0]};
            const real l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            const real lu = std::sqrt(su[0] * su[0] + su[1] * su[1] + su[2] * su[2]);
            const real lv = std::sqrt(sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]);
            if (!(l > 1e-3L * lu * lv)) continue;
            const real sign = mean[0] * n[0] + mean[1] * n[1] + mean[2] * n[2] < 0 ? -1 : 1;
            for (int k = 0; k < 3; ++k) mean[k] += sign * n[k] / l;
        }
        const real l = std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
        c.has_normal = l > 1e-6L;
        for (int k = 0; k < 3; ++k) c.normal[k] = c.has_normal ? mean[k] / l : 0;
        corners.push_back(c);
    }
    return corners;
}

std::vector<CollapsedPoint> find_collapsed_points(const std::vector<ref::Patch> &patches) {
    std::vector<Point> points;
    for (const ref::Patch &patch : patches)
        for (int e = 0; e < 4; ++e) {
            const EdgeKey edge = edge_points(patch, e);
            if (collapsed(edge) && std::find(points.begin(), points.end(), edge[0]) == points.end())
                points.push_back(edge[0]);
        }
    std::vector<CollapsedPoint> out;
    for (const Point &p : points) out.push_back({{p[0], p[1], p[2]}});
    return out;
}

} // namespace bench
