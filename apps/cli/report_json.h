// JSON serialisation of query results (schema documented in docs/report.md).
#pragma once
#include <nlohmann/json.hpp>

#include "interfere/query/clash.h"
#include "interfere/query/distance.h"

namespace interfere::cli {

nlohmann::json vec_json(const Vec3& v);
nlohmann::json box_json(const Aabb& b);
nlohmann::json clash_result_json(const ClashResult& r, std::size_t max_clearance_pairs);
nlohmann::json distance_result_json(const DistanceResult& r);
const char* kind_name(ContactKind k);

}  // namespace interfere::cli
