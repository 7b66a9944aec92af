#pragma once
// The names users give the pipeline's choices, shared by the command line and the Python module so
// that both accept the same words.

#include <map>
#include <string>

#include "vesselmesh/pipeline.hpp"

namespace vesselmesh {

inline const std::map<std::string, Sampling>& sampling_names() {
  static const std::map<std::string, Sampling> names{{"bidirectional", Sampling::bidirectional},
                                                     {"unidirectional", Sampling::unidirectional}};
  return names;
}

inline const std::map<std::string, Caps>& caps_names() {
  static const std::map<std::string, Caps> names{{"flat", Caps::flat}, {"open", Caps::open}};
  return names;
}

inline const std::map<std::string, Crossings>& crossings_names() {
  static const std::map<std::string, Crossings> names{{"separate", Crossings::separate},
                                                      {"keep", Crossings::keep}};
  return names;
}

inline const std::map<std::string, Fit>& fit_names() {
  static const std::map<std::string, Fit> names{
      {"onto", Fit::onto}, {"inward", Fit::inward}, {"none", Fit::none}};
  return names;
}

inline const std::map<std::string, Verify>& verify_names() {
  static const std::map<std::string, Verify> names{
      {"auto", Verify::automatic}, {"full", Verify::full}, {"topology", Verify::topology}};
  return names;
}

inline const std::map<std::string, Refinement>& refinement_names() {
  static const std::map<std::string, Refinement> names{
      {"curvature", Refinement::curvature}, {"uniform", Refinement::uniform}, {"dihedral", Refinement::dihedral}};
  return names;
}

inline const std::map<std::string, CurvatureMeasure>& measure_names() {
  static const std::map<std::string, CurvatureMeasure> names{
      {"tube-departure", CurvatureMeasure::tube_departure}, {"gaussian", CurvatureMeasure::gaussian},
      {"abs-gaussian", CurvatureMeasure::abs_gaussian},     {"mean", CurvatureMeasure::mean},
      {"abs-mean", CurvatureMeasure::abs_mean},             {"rms", CurvatureMeasure::rms}};
  return names;
}

}  // namespace vesselmesh
