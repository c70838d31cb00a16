#pragma once
/// An allocator whose memory starts zeroed (calloc: a large block is fresh pages from the kernel,
/// zero until first touched, never written by us) and whose default-inserted elements are left
/// as they are: `std::vector<float, ZeroedAllocator<float>> v; v.resize(n);` gives n zeros
/// without a fill pass. Explicit values (resize(n, v), assign, push_back) are written as usual.
#include <cstddef>
#include <cstdlib>
#include <new>
#include <utility>

namespace kasumi {

template <class T>
struct ZeroedAllocator {
    using value_type = T;
    ZeroedAllocator() = default;
    template <class U>
    ZeroedAllocator(const ZeroedAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (void* p = std::calloc(n, sizeof(T)))
            return static_cast<T*>(p);
        throw std::bad_alloc();
    }
    void deallocate(T* p, std::size_t) noexcept { std::free(p); }
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;  // default-initialised: the zeros calloc gave
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    template <class U>
    bool operator==(const ZeroedAllocator<U>&) const noexcept {
        return true;
    }
    template <class U>
    bool operator!=(const ZeroedAllocator<U>&) const noexcept {
        return false;
    }
};

}  // namespace kasumi
