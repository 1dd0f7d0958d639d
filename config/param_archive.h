#pragma once
// One description per parameter struct (in the manner of Drake's Serialize/name-value pairs),
// from which come the strict YAML/--set loader, validation, the documented defaults and the dump:
//
//   template <typename Archive>
//   void Serialize(Archive* a, TraverseParameters* p) {      // next to the struct's loader header
//     a->Visit(APERTURE_NVP(p, max_start_speed_mps));          // key = field name (units in it)
//     a->Visit(APERTURE_NVP(p, mode), kModeNames);             // enum: {{"fast", Mode::kFast}, ..}
//     a->Visit(APERTURE_NVP(p, limits));                       // nested struct: a sub-map
//   }
//
//   config::ParamReader reader = tree.Reader().Section("traverse");
//   LoadParams(reader, &params);          // YamlReadArchive: absent keys keep the defaults,
//                                         // unknown keys and type errors name file:line and key,
//                                         // then the struct's Validate() (ValidateParams hook)
//   YAML::Node node = DumpParams(params); // YamlWriteArchive: every field, reloadable exactly
//
// Archives (YamlReadArchive in yaml_read_archive.h, YamlWriteArchive in yaml_write_archive.h)
// offer: Visit(name, &field), Visit(name, &enum_field, names), VisitSection(name, function) for a
// sub-map whose fields a function describes, VisitLimit(name, &double_field) for a number that may
// be .inf/-.inf meaning "no limit" (ParamReader::ReadLimit; elsewhere infinity is an error), and
// kLoading for the rare field that only exists in the file (a preset name standing for several
// fields). Leaf types are those of ConvertNode (param_reader.h) and EncodeNode
// (yaml_write_archive.h); a struct's own leaf format (e.g. a gust as [t, duration, wx, wy, wz]) is
// a ConvertNode/EncodeNode overload pair in its namespace.
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

// Expands to the two arguments "field", &(object)->field of Archive::Visit.
#define APERTURE_NVP(object, field) #field, &(object)->field

namespace aperture::config {

template <typename Enum>
using EnumNames = std::vector<std::pair<std::string, Enum>>;

namespace internal {

// Archive type used only to ask whether Serialize(Archive*, T*) exists for T.
struct ProbeArchive {
  static constexpr bool kLoading = true;
  template <typename T>
  void Visit(const char*, T*) {}
  template <typename T, typename Enum>
  void Visit(const char*, T*, const EnumNames<Enum>&) {}
  template <typename Function>
  void VisitSection(const char*, const Function&) {}
  void VisitLimit(const char*, double*) {}
};

template <typename T, typename = void>
struct HasSerialize : std::false_type {};
template <typename T>
struct HasSerialize<
    T, std::void_t<decltype(Serialize(std::declval<ProbeArchive*>(), std::declval<T*>()))>>
    : std::true_type {};

template <typename T, typename = void>
struct HasValidateMember : std::false_type {};
template <typename T>
struct HasValidateMember<T, std::void_t<decltype(std::declval<const T&>().Validate())>>
    : std::true_type {};

template <typename T, typename = void>
struct HasValidateHook : std::false_type {};
template <typename T>
struct HasValidateHook<T, std::void_t<decltype(ValidateParams(std::declval<const T&>()))>>
    : std::true_type {};

}  // namespace internal

// True when a Serialize(Archive*, T*) overload describes T (found by argument-dependent lookup).
template <typename T>
inline constexpr bool kIsSerializable = internal::HasSerialize<T>::value;

// The validation of a loaded struct: a ValidateParams(const T&) overload in T's namespace when
// there is one (a free validator, or none for a struct only valid once assembled), else T's
// Validate() member, else nothing. Throws what the validator throws.
template <typename T>
void ValidateLoaded(const T& params) {
  if constexpr (internal::HasValidateHook<T>::value) {
    ValidateParams(params);
  } else if constexpr (internal::HasValidateMember<T>::value) {
    params.Validate();
  }
}

}  // namespace aperture::config
