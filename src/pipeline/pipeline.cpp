#include "pipeline/pipeline.hpp"

namespace j232::pipeline {

const Pipeline& j232_test();       // pipeline/j232_pipeline.cpp
const Pipeline& field_pipeline();  // pipeline/field_pipeline.cpp

const Pipeline& pipeline_of(const scenario::Scenario& s) { return s.field.present ? field_pipeline() : j232_test(); }
const Pipeline& pipeline_of(const toml::table& scenario_file) { return scenario_file.contains("field") ? field_pipeline() : j232_test(); }

}  // namespace j232::pipeline
