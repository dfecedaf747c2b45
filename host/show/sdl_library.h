// SDL2, loaded when the viewer first opens a window rather than linked: SDL2 brings some forty
// libraries (X11, Wayland, PulseAudio, ...) that every other subcommand would otherwise load
// at start-up. The functions the viewer calls, with SDL's own signatures.
#pragma once

#include <SDL.h>

namespace evms::show {

struct SdlLibrary {
  decltype(&SDL_Init) Init;
  decltype(&SDL_Quit) Quit;
  decltype(&SDL_GetError) GetError;
  decltype(&SDL_GetCurrentVideoDriver) GetCurrentVideoDriver;
  decltype(&SDL_CreateWindow) CreateWindow;
  decltype(&SDL_DestroyWindow) DestroyWindow;
  decltype(&SDL_CreateRenderer) CreateRenderer;
  decltype(&SDL_DestroyRenderer) DestroyRenderer;
  decltype(&SDL_CreateTexture) CreateTexture;
  decltype(&SDL_DestroyTexture) DestroyTexture;
  decltype(&SDL_UpdateTexture) UpdateTexture;
  decltype(&SDL_RenderClear) RenderClear;
  decltype(&SDL_RenderCopy) RenderCopy;
  decltype(&SDL_RenderPresent) RenderPresent;
  decltype(&SDL_PollEvent) PollEvent;
};

// The library, loaded on the first call; throws std::runtime_error naming the library and what
// the loader said when it is not installed.
const SdlLibrary& sdl();

}  // namespace evms::show
