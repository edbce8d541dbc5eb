#include <interfere/mesh/generate.h>
#include <interfere/query/clash.h>

int main() {
  using namespace interfere;
  const Model a = make_model(make_box({0, 0, 0}, {1, 1, 1}));
  const Model b = make_model(make_box({0.5, 0.5, 0.5}, {2, 2, 2}));
  return clash(a, b).cross_pairs > 0 ? 0 : 1;
}
