#include <string>

#include "ptnet/shop.hpp"

namespace ptnet {

void (*closer)(int) = &ptnet::close_shop;

// A parameter of the function's name is no use of the function.
std::string label(const std::string& shop_name, int id) { return shop_name + std::to_string(id); }

}  // namespace ptnet
