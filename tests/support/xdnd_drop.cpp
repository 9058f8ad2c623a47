// A drag-and-drop source for the viewer's tests: drops one file on an X window as a file manager
// does, by the XDND protocol (freedesktop.org, "Drag-and-Drop Protocol for the X Window System",
// version 5): enter, position at the window's middle, drop once the window accepts, the file's
// URI served as text/uri-list when the window asks for the selection, done when it says it
// finished. xdotool moves, clicks and types, but cannot drag a file.
//
// Usage: xdnd_drop WINDOW FILE, on the display $DISPLAY names (WINDOW: an X window id, as
// `xdotool search` prints it; FILE: an absolute path). Exits 0 when the window finished the drop,
// 1 when it refused it or did not answer within 30 s, 2 on a usage error.
#include <X11/Xlib.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: xdnd_drop WINDOW FILE\n");
    return 2;
  }
  Display* display = XOpenDisplay(nullptr);
  if (!display) {
    std::fprintf(stderr, "xdnd_drop: cannot open the display\n");
    return 1;
  }
  const Window target = std::strtoul(argv[1], nullptr, 0);
  const std::string uri = "file://" + std::string(argv[2]) + "\r\n";
  const auto atom = [&](const char* name) { return XInternAtom(display, name, False); };
  const Atom enter = atom("XdndEnter"), position = atom("XdndPosition"),
             status = atom("XdndStatus"), drop = atom("XdndDrop"), finished = atom("XdndFinished"),
             selection = atom("XdndSelection"), copy = atom("XdndActionCopy"),
             uriList = atom("text/uri-list");
  const Window root = DefaultRootWindow(display);
  const Window source = XCreateSimpleWindow(display, root, 0, 0, 1, 1, 0, 0, 0);
  XSetSelectionOwner(display, selection, source, CurrentTime);
  // The window's middle, in root coordinates (XdndPosition's).
  XWindowAttributes attributes;
  XGetWindowAttributes(display, target, &attributes);
  int x = 0, y = 0;
  Window child = 0;
  XTranslateCoordinates(display, target, root, attributes.width / 2, attributes.height / 2, &x, &y,
                        &child);
  const auto send = [&](Atom type, long l1, long l2, long l3, long l4) {
    XEvent e{};
    e.xclient.type = ClientMessage;
    e.xclient.display = display;
    e.xclient.window = target;
    e.xclient.message_type = type;
    e.xclient.format = 32;
    e.xclient.data.l[0] = static_cast<long>(source);
    e.xclient.data.l[1] = l1;
    e.xclient.data.l[2] = l2;
    e.xclient.data.l[3] = l3;
    e.xclient.data.l[4] = l4;
    XSendEvent(display, target, False, NoEventMask, &e);
    XFlush(display);
  };
  // Version 5 in the top byte; up to three types in the message itself.
  send(enter, 5L << 24, static_cast<long>(uriList), 0, 0);
  send(position, 0, (static_cast<long>(x) << 16) | y, CurrentTime, static_cast<long>(copy));
  bool dropped = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < deadline) {
    while (XPending(display)) {
      XEvent e;
      XNextEvent(display, &e);
      if (e.type == ClientMessage && e.xclient.message_type == status && !dropped) {
        if (!(e.xclient.data.l[1] & 1)) {
          std::fprintf(stderr, "xdnd_drop: the window refuses the drop\n");
          return 1;
        }
        send(drop, 0, CurrentTime, 0, 0);
        dropped = true;
      } else if (e.type == SelectionRequest) {
        // The window asks for the dragged data: the URI list, in the property it names.
        const XSelectionRequestEvent& r = e.xselectionrequest;
        XChangeProperty(display, r.requestor, r.property, r.target, 8, PropModeReplace,
                        reinterpret_cast<const unsigned char*>(uri.data()),
                        static_cast<int>(uri.size()));
        XEvent reply{};
        reply.xselection.type = SelectionNotify;
        reply.xselection.display = display;
        reply.xselection.requestor = r.requestor;
        reply.xselection.selection = r.selection;
        reply.xselection.target = r.target;
        reply.xselection.property = r.property;
        reply.xselection.time = r.time;
        XSendEvent(display, r.requestor, False, NoEventMask, &reply);
        XFlush(display);
      } else if (e.type == ClientMessage && e.xclient.message_type == finished) {
        XCloseDisplay(display);
        return 0;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::fprintf(stderr, "xdnd_drop: no answer from window 0x%lx\n", target);
  return 1;
}
