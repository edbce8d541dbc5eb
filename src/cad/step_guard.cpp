// Guards around OpenCASCADE's STEP reader: see step_guard.h.
#include "step_guard.h"

#include <Interface_Check.hxx>
#include <Interface_EntityIterator.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <OSD.hxx>
#include <TCollection_HAsciiString.hxx>

#include <algorithm>
#include <cstdint>

namespace interfere::cad::detail {

Fails fails_of(const Interface_CheckIterator& checks, const Handle(Interface_InterfaceModel)& model, bool global) {
  Fails f;
  Interface_CheckIterator it = checks;  // (copies share the cursor: start it)
  for (it.Start(); it.More(); it.Next()) {
    const Handle(Interface_Check)& c = it.Value();
    if (c.IsNull() || !c->HasFailed() || (it.Number() <= 0) != global) continue;
    for (int i = 1; i <= c->NbFails(); ++i, ++f.count) {
      if (f.count >= 3) continue;
      std::string where;
      if (it.Number() > 0 && !model.IsNull() && it.Number() <= model->NbEntities()) {
        const Handle(TCollection_HAsciiString) label = model->StringLabel(model->Value(it.Number()));
        if (!label.IsNull()) where = std::string("entity ") + label->ToCString() + ": ";
      }
      f.first += (f.first.empty() ? "" : "; ") + where + c->CFail(i);
    }
  }
  return f;
}

// Iterative depth-first search over the reference graph (compressed rows of each entity's shared
// entities); an entity met again while on the current path closes a cycle.
std::string reference_cycle(const Interface_Graph& graph, const Handle(Interface_InterfaceModel)& model) {
  const int n = model->NbEntities();
  std::vector<int> start(static_cast<std::size_t>(n) + 2, 0), refs;
  for (int i = 1; i <= n; ++i) {
    start[i] = static_cast<int>(refs.size());
    for (Interface_EntityIterator it = graph.Shareds(model->Value(i)); it.More(); it.Next())
      if (const int j = model->Number(it.Value()); j > 0) refs.push_back(j);
  }
  start[n + 1] = static_cast<int>(refs.size());
  std::vector<std::uint8_t> state(static_cast<std::size_t>(n) + 1, 0);  // 0 new, 1 on the path, 2 done
  std::vector<std::pair<int, int>> path;                                // entity, next reference
  for (int root = 1; root <= n; ++root) {
    if (state[root]) continue;
    state[root] = 1;
    path.push_back({root, start[root]});
    while (!path.empty()) {
      auto& [e, next] = path.back();
      if (next == start[e + 1]) {
        state[e] = 2;
        path.pop_back();
        continue;
      }
      const int j = refs[next++];
      if (state[j] == 1) {
        const Handle(TCollection_HAsciiString) label = model->StringLabel(model->Value(j));
        return label.IsNull() ? "#?" : label->ToCString();
      }
      if (state[j] == 0) {
        state[j] = 1;
        path.push_back({j, start[j]});
      }
    }
  }
  return {};
}

void CollectingPrinter::send(const TCollection_AsciiString& text, const Message_Gravity gravity) const {
  if (gravity < Message_Fail || fails.size() >= 8) return;
  std::string t = text.ToCString();
  const auto junk = [](char c) { return c == '\n' || c == ' ' || c == '*'; };  // "**** ERR ... ****"
  while (!t.empty() && junk(t.back())) t.pop_back();
  t.erase(0, static_cast<std::size_t>(std::find_if_not(t.begin(), t.end(), junk) - t.begin()));
  if (!t.empty()) fails.push_back(t);
}

OcctSignals::OcctSignals() {
  for (std::size_t i = 0; i < kSignals.size(); ++i) sigaction(kSignals[i], nullptr, &saved_[i]);
  OSD::SetSignal(OSD_SignalMode_Set, Standard_False);
}

OcctSignals::~OcctSignals() {
  for (std::size_t i = 0; i < kSignals.size(); ++i) sigaction(kSignals[i], &saved_[i], nullptr);
}

QuietOcct::QuietOcct() : saved_(Message::DefaultMessenger()->Printers()), printer_(new CollectingPrinter) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  Message::DefaultMessenger()->AddPrinter(printer_);
}

QuietOcct::~QuietOcct() { Message::DefaultMessenger()->ChangePrinters() = saved_; }

std::string QuietOcct::fails() const {
  std::string out;
  for (const std::string& f : printer_->fails) out += (out.empty() ? "" : "; ") + f;
  return out;
}

}  // namespace interfere::cad::detail
