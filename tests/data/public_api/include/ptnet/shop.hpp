// ptnet/shop.hpp: a stage's public header (a fixture of
// tests/check_public_api_test.sh).
#pragma once

#include <string>

namespace ptnet {

int open_shop(int id);
void close_shop(int id);
std::string shop_name(int id);
int count_items(int id);
double price_of(int item);

}  // namespace ptnet
