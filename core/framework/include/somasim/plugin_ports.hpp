#pragma once
/// @file
/// Ports declared once: a plugin's inputs and outputs are members of a struct, named once in
/// its `visit`; the spec's port list and the binding to the run's storage both come from it.
/// @code
///   struct Ports {
///     In<JointState> state;
///     OptionalIn<JointTarget> target;
///     Out<JointCommand> command;
///     template <class V> void visit(V& v) {
///       v.port("state", state, "measured joint state");
///       v.port("target", target, "new goals");  // optional: may be left unwired
///       v.port("command", command, "position commands");
///     }
///   };
///   // Ports several plugins share are a struct of their own, embedded with v.block(member).
///   // in configure(): bind_ports(ctx, ports_); then *ports_.state, ports_.command->...
/// @endcode
#include <string>

#include "somasim/config.hpp"
#include "somasim/error.hpp"
#include "somasim/plugin.hpp"

namespace somasim {

/// A required input: the value wired to it, read-only, valid from configure() on.
template <class T>
class In {
 public:
  const T& operator*() const { return *value_; }
  const T* operator->() const { return value_; }
  const T& get() const { return *value_; }
  /// False before bind_ports() (e.g. in finish() after configure() failed).
  bool bound() const { return value_ != nullptr; }

 private:
  friend class PortBinder;
  const T* value_ = nullptr;
};

/// An input that may be left unwired: check wired() (or get() != nullptr) before reading.
template <class T>
class OptionalIn {
 public:
  bool wired() const { return value_ != nullptr; }
  explicit operator bool() const { return wired(); }
  const T* get() const { return value_; }  ///< nullptr when unwired
  const T& operator*() const { return *value_; }
  const T* operator->() const { return value_; }

 private:
  friend class PortBinder;
  const T* value_ = nullptr;
};

/// An output: the node's storage, written in step().
template <class T>
class Out {
 public:
  T& operator*() const { return *value_; }
  T* operator->() const { return value_; }
  T& get() const { return *value_; }
  /// False before bind_ports() (e.g. in finish() after configure() failed).
  bool bound() const { return value_ != nullptr; }

 private:
  friend class PortBinder;
  T* value_ = nullptr;
};

/// Visitor that declares the ports in a spec.
class PortDeclarer {
 public:
  explicit PortDeclarer(PluginSpec& spec) : spec_(spec) {}
  template <class T>
  void port(const std::string& name, In<T>&, const std::string& doc) {
    spec_.input<T>(name, doc);
  }
  template <class T>
  void port(const std::string& name, OptionalIn<T>&, const std::string& doc) {
    spec_.input<T>(name, doc, /*optional=*/true);
  }
  template <class T>
  void port(const std::string& name, Out<T>&, const std::string& doc) {
    spec_.output<T>(name, doc);
  }
  /// Ports of a shared block (a struct with its own visit), in its visit order.
  template <class B>
  void block(B& b) {
    b.visit(*this);
  }

 private:
  PluginSpec& spec_;
};

/// Visitor that binds the members to a node's storage.
class PortBinder {
 public:
  explicit PortBinder(NodeContext& ctx) : ctx_(ctx) {}
  template <class T>
  void port(const std::string& name, In<T>& p, const std::string&) {
    p.value_ = &ctx_.input<T>(name);
  }
  template <class T>
  void port(const std::string& name, OptionalIn<T>& p, const std::string&) {
    p.value_ = ctx_.is_wired(name) ? &ctx_.input<T>(name) : nullptr;
  }
  template <class T>
  void port(const std::string& name, Out<T>& p, const std::string&) {
    p.value_ = &ctx_.output<T>(name);
  }
  template <class B>
  void block(B& b) {
    b.visit(*this);
  }

 private:
  NodeContext& ctx_;
};

/// Adds the ports of struct P to `spec`, in visit order.
template <class P>
void declare_ports(PluginSpec& spec) {
  P ports{};
  PortDeclarer declarer(spec);
  ports.visit(declarer);
}

/// Binds every member of `ports` to the node's storage (call it in configure()).
template <class P>
void bind_ports(NodeContext& ctx, P& ports) {
  PortBinder binder(ctx);
  ports.visit(binder);
}

/// A plugin spec generated from a config struct C (parameters) and a port struct P.
template <class C, class P>
PluginSpec make_plugin_spec(std::string name, std::string doc) {
  PluginSpec spec(std::move(name), std::move(doc));
  for (ParamSpec& p : config_schema<C>()) spec.add_param(std::move(p));
  declare_ports<P>(spec);
  return spec;
}

}  // namespace somasim
