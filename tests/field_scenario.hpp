#pragma once
// A small field for the tests (tests/test_field.cpp, tests/test_uncertainty.cpp): a 21-in
// mower (kMower) and a field of stones before it with a traffic lane beside it (kStones).
#include <string>

namespace j232::test {

const std::string kMower = R"(
title = "field test mower"
[blade]
speed = "2700 rpm"
height = "2 in"
[blade.hub]
bar_mass = "3.5 lb"
bar_length = "21 in"
[housing]
skirt_bottom = "3 in"
)";
// Every stone lies on the plane the wheels ride on (support_height 0), so that the tests of
// reach, strata and tallies have closed forms; the support's own tests set it.
const std::string kStones = R"(
[field]
objects_simulated = 4000
support_height = "0 mm"
[[field.objects]]
name = "stones"
median_size = "30 mm"
spread = 1.6
min_size = "10 mm"
max_size = "70 mm"
per_area = "0.5 m^-2"
embedment = 0.2
[[field.planes]]
name = "lane"
side = "right"
distance = "4 m"
receptor = "vehicle"
)";

}  // namespace j232::test
