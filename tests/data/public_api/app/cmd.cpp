#include <algorithm>
#include <string>
#include <vector>

#include "ptnet/shop.hpp"

struct Sign {
  std::string shop_name() const { return "sign"; }
};

using PriceFn = double (*)(int);

namespace ptnet {
PriceFn pricing() { return &price_of; }  // address-of
}  // namespace ptnet

int run(const std::vector<int>& ids) {
  std::string shop_name("corner");  // a variable, not a call
  Sign s;
  shop_name += s.shop_name();       // a member's call
  std::vector<int> counts(ids.size());
  std::transform(ids.begin(), ids.end(), counts.begin(), ptnet::count_items);
  return ptnet::open_shop(int(shop_name.size()));
}
