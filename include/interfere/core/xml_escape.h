// Text as XML character data or attribute value: & < > " ' as entity references. One escape for
// every XML the project writes (VTK XML in fem/io/vtu_write.cpp and view/pvd.cpp).
#pragma once
#include <string>
#include <string_view>

namespace interfere {

std::string xml_escape(std::string_view text);

}  // namespace interfere
