#include "ptnet/shop.hpp"

namespace ptnet {

int open_shop(int id) { return id; }
void close_shop(int) {}
std::string shop_name(int id) { return "shop " + std::to_string(open_shop(id)); }
int count_items(int id) { return id * 2; }
double price_of(int item) { return item * 0.5; }

}  // namespace ptnet
