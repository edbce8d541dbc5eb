// Guards around OpenCASCADE 7.6's STEP reader (issue #6, "Bad input"; src/cad only): its recorded
// failures as text, a reference-cycle check to run before its entity checks (which recurse along
// cycles until the stack overflows), its signals converted to exceptions for the duration of an
// import, and its stdout messages collected instead of printed.
#pragma once
#include <Interface_CheckIterator.hxx>
#include <Interface_Graph.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Message_Printer.hxx>
#include <Message_SequenceOfPrinters.hxx>

#include <array>
#include <csignal>
#include <string>
#include <vector>

namespace interfere::cad::detail {

/// The failures OCCT recorded, global ones (the file's syntax, unresolved references: entity
/// number 0) or those of entities (schema checks, translation): their count and the first three
/// with their STEP ids.
struct Fails {
  std::size_t count = 0;
  std::string first;
  std::string text() const { return first + (count > 3 ? "; ..." : ""); }
};
Fails fails_of(const Interface_CheckIterator& checks, const Handle(Interface_InterfaceModel)& model, bool global);

/// A cycle of references (#a -> #b -> ... -> #a; a mistyped reference can make one, e.g. an
/// oriented edge whose edge is itself): the STEP id of an entity on it, or empty.
std::string reference_cycle(const Interface_Graph& graph, const Handle(Interface_InterfaceModel)& model);

/// Collects the failure messages OCCT sends (the parser's syntax errors name the line).
class CollectingPrinter : public Message_Printer {
 public:
  mutable std::vector<std::string> fails;

 protected:
  void send(const TCollection_AsciiString& text, const Message_Gravity gravity) const override;
};

/// OSD::SetSignal (signals inside OCCT become Standard_Failure exceptions at the nearest
/// OCC_CATCH_SIGNALS) for the lifetime of the object; the previous handlers (the host's: Python's,
/// a GUI's) are restored afterwards.
class OcctSignals {
 public:
  OcctSignals();
  ~OcctSignals();
  OcctSignals(const OcctSignals&) = delete;
  OcctSignals& operator=(const OcctSignals&) = delete;

 private:
  static constexpr std::array<int, 9> kSignals{SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGINT, SIGQUIT, SIGHUP, SIGTERM, SIGSYS};
  std::array<struct sigaction, kSignals.size()> saved_{};
};

/// OCCT prints the reader's messages to stdout (its default messenger): for the lifetime of the
/// object they are collected instead, and the printers restored after.
class QuietOcct {
 public:
  QuietOcct();
  ~QuietOcct();
  QuietOcct(const QuietOcct&) = delete;
  QuietOcct& operator=(const QuietOcct&) = delete;
  /// The failures OCCT reported so far, "; "-separated (empty: none).
  std::string fails() const;

 private:
  Message_SequenceOfPrinters saved_;
  Handle(CollectingPrinter) printer_;
};

}  // namespace interfere::cad::detail
