#pragma once
// YamlReadArchive: the loading side of a struct's Serialize (param_archive.h), on a
// config::ParamReader, so every error keeps the reader's quality: the file:line or --set item,
// the full dotted key and what was expected (the type, the allowed names, the known keys).
//
//   config::ParamReader reader = tree.Reader().Section("mission");
//   LoadParams(reader, &mission_params);   // or root.ReadSection("mission", &mission_params)
#include "config/param_archive.h"
#include "config/param_reader.h"

namespace aperture::config {

class YamlReadArchive {
 public:
  static constexpr bool kLoading = true;

  explicit YamlReadArchive(ParamReader* reader) : reader_(reader) {}

  // A present key overwrites the field (a nested Serialize-described struct: its sub-map, read
  // with LoadParams, so absent keys inside keep their values); an absent key leaves it.
  template <typename T>
  void Visit(const char* name, T* value) {
    if constexpr (kIsSerializable<T>) {
      reader_->ReadSection(name, value);
    } else {
      reader_->Read(name, value);
    }
  }
  template <typename Enum>
  void Visit(const char* name, Enum* value, const EnumNames<Enum>& names) {
    reader_->ReadEnum(name, value, names);
  }
  // A number for which .inf/-.inf mean "no limit" (ParamReader::ReadLimit).
  void VisitLimit(const char* name, double* value) { reader_->ReadLimit(name, value); }
  // The sub-map `name`, whose fields `describe(archive)` visits (e.g. a subset of a struct's
  // fields); unknown keys inside are rejected.
  template <typename Function>
  void VisitSection(const char* name, const Function& describe) {
    ParamReader section = reader_->Section(name);
    YamlReadArchive archive(&section);
    describe(&archive);
    section.RejectUnknownKeys();
  }

  // For checks a Serialize makes itself (Where, FullKey in its error messages).
  ParamReader& reader() { return *reader_; }

 private:
  ParamReader* reader_;
};

// Loads every field Serialize(archive, params) names from `reader`'s map (absent keys keep the
// current values), rejects unknown keys and validates the result (ValidateLoaded), the error
// prefixed with the section's location. Found by argument-dependent lookup through the reader.
template <typename T, typename = std::enable_if_t<kIsSerializable<T>>>
void LoadParams(ParamReader& reader, T* params) {
  YamlReadArchive archive(&reader);
  Serialize(&archive, params);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

}  // namespace aperture::config
