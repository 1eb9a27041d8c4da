// FunctionRef: a non-owning reference to a callable, for passing lambdas to
// non-template functions without std::function's allocation.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>

namespace pt {

// A non-owning reference to a callable (like std::function_ref): no allocation,
// one indirect call. The referenced callable must outlive the FunctionRef.
template <class Signature>
class FunctionRef;

template <class R, class... Args>
class FunctionRef<R(Args...)> {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, FunctionRef>>>
  FunctionRef(F&& f)  // NOLINT: implicit by design
      : obj_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
        call_([](void* o, Args... args) -> R {
          return (*static_cast<std::add_pointer_t<std::remove_reference_t<F>>>(o))(std::forward<Args>(args)...);
        }) {}

  R operator()(Args... args) const { return call_(obj_, std::forward<Args>(args)...); }

 private:
  void* obj_;
  R (*call_)(void*, Args...);
};

}  // namespace pt
