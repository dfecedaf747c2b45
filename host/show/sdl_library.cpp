#include "host/show/sdl_library.h"

#include <dlfcn.h>

#include <stdexcept>
#include <string>

namespace evms::show {
namespace {

constexpr const char* kSoname = "libSDL2-2.0.so.0";

template <class F>
void resolve(void* handle, F& f, const char* name) {
  void* symbol = dlsym(handle, name);
  if (!symbol) throw std::runtime_error(std::string(kSoname) + " has no " + name + ": " + dlerror());
  f = reinterpret_cast<F>(symbol);
}

SdlLibrary load() {
  void* handle = dlopen(kSoname, RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw std::runtime_error(std::string("cannot load SDL2 for the window (") + dlerror() + "): install libsdl2-2.0-0");
  SdlLibrary l{};
  resolve(handle, l.Init, "SDL_Init");
  resolve(handle, l.Quit, "SDL_Quit");
  resolve(handle, l.GetError, "SDL_GetError");
  resolve(handle, l.GetCurrentVideoDriver, "SDL_GetCurrentVideoDriver");
  resolve(handle, l.CreateWindow, "SDL_CreateWindow");
  resolve(handle, l.DestroyWindow, "SDL_DestroyWindow");
  resolve(handle, l.CreateRenderer, "SDL_CreateRenderer");
  resolve(handle, l.DestroyRenderer, "SDL_DestroyRenderer");
  resolve(handle, l.CreateTexture, "SDL_CreateTexture");
  resolve(handle, l.DestroyTexture, "SDL_DestroyTexture");
  resolve(handle, l.UpdateTexture, "SDL_UpdateTexture");
  resolve(handle, l.RenderClear, "SDL_RenderClear");
  resolve(handle, l.RenderCopy, "SDL_RenderCopy");
  resolve(handle, l.RenderPresent, "SDL_RenderPresent");
  resolve(handle, l.PollEvent, "SDL_PollEvent");
  return l;  // the handle stays open for the life of the process
}

}  // namespace

const SdlLibrary& sdl() {
  static const SdlLibrary library = load();
  return library;
}

}  // namespace evms::show
