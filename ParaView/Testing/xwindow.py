# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""What a user does to ParaView's window, done through Xlib (ctypes, libX11 only: the GUI tests
run on a bare Xvfb, without a window manager or xdotool): find a top-level window by its title,
resize it, and read back what the X server shows (the pixels a user sees, not a re-render).

    python3 xwindow.py find <title part>                 prints the window id or exits 1
    python3 xwindow.py list                              the viewable top-level windows
    python3 xwindow.py resize <id> <width> <height>
    python3 xwindow.py drag <x0> <y0> <x1> <y1>          a left-button drag, screen pixels
    python3 xwindow.py capture <id> <file.npy>           RGB, rows top to bottom
"""
import ctypes
import ctypes.util
import sys

_x11 = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
_x11.XOpenDisplay.restype = ctypes.c_void_p
_x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
_x11.XDefaultRootWindow.restype = ctypes.c_ulong
_x11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
_x11.XQueryTree.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(ctypes.c_ulong),
                            ctypes.POINTER(ctypes.c_ulong),
                            ctypes.POINTER(ctypes.POINTER(ctypes.c_ulong)),
                            ctypes.POINTER(ctypes.c_uint)]
_x11.XFetchName.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(ctypes.c_char_p)]
_x11.XFree.argtypes = [ctypes.c_void_p]
_x11.XMoveResizeWindow.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int,
                                   ctypes.c_uint, ctypes.c_uint]
_x11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
_x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
_x11.XGetImage.restype = ctypes.c_void_p
_x11.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int,
                           ctypes.c_uint, ctypes.c_uint, ctypes.c_ulong, ctypes.c_int]
_xtst = ctypes.CDLL(ctypes.util.find_library("Xtst") or "libXtst.so.6")
_xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int,
                                       ctypes.c_ulong]
_xtst.XTestFakeButtonEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int,
                                       ctypes.c_ulong]


class _WindowAttributes(ctypes.Structure):
    _fields_ = [("x", ctypes.c_int), ("y", ctypes.c_int), ("width", ctypes.c_int),
                ("height", ctypes.c_int), ("border_width", ctypes.c_int),
                ("depth", ctypes.c_int), ("visual", ctypes.c_void_p),
                ("root", ctypes.c_ulong), ("class_", ctypes.c_int),
                ("bit_gravity", ctypes.c_int), ("win_gravity", ctypes.c_int),
                ("backing_store", ctypes.c_int), ("backing_planes", ctypes.c_ulong),
                ("backing_pixel", ctypes.c_ulong), ("save_under", ctypes.c_int),
                ("colormap", ctypes.c_ulong), ("map_installed", ctypes.c_int),
                ("map_state", ctypes.c_int), ("all_event_masks", ctypes.c_long),
                ("your_event_mask", ctypes.c_long), ("do_not_propagate_mask", ctypes.c_long),
                ("override_redirect", ctypes.c_int), ("screen", ctypes.c_void_p)]


_x11.XGetWindowAttributes.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                      ctypes.POINTER(_WindowAttributes)]


class _XImage(ctypes.Structure):
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("xoffset", ctypes.c_int),
                ("format", ctypes.c_int), ("data", ctypes.POINTER(ctypes.c_ubyte)),
                ("byte_order", ctypes.c_int), ("bitmap_unit", ctypes.c_int),
                ("bitmap_bit_order", ctypes.c_int), ("bitmap_pad", ctypes.c_int),
                ("depth", ctypes.c_int), ("bytes_per_line", ctypes.c_int),
                ("bits_per_pixel", ctypes.c_int), ("red_mask", ctypes.c_ulong),
                ("green_mask", ctypes.c_ulong), ("blue_mask", ctypes.c_ulong),
                ("obdata", ctypes.c_void_p), ("f_create_image", ctypes.c_void_p),
                ("f_destroy_image", ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p))]


class Display:
    """One connection to $DISPLAY."""

    def __init__(self):
        self.handle = _x11.XOpenDisplay(None)
        if not self.handle:
            raise RuntimeError("cannot open the X display")

    def close(self):
        _x11.XCloseDisplay(self.handle)

    def _children(self, window):
        root, parent = ctypes.c_ulong(), ctypes.c_ulong()
        children, count = ctypes.POINTER(ctypes.c_ulong)(), ctypes.c_uint()
        if not _x11.XQueryTree(self.handle, window, ctypes.byref(root), ctypes.byref(parent),
                               ctypes.byref(children), ctypes.byref(count)):
            return []
        found = [children[i] for i in range(count.value)]
        if children:
            _x11.XFree(children)
        return found

    def name(self, window):
        name = ctypes.c_char_p()
        if _x11.XFetchName(self.handle, window, ctypes.byref(name)) and name.value is not None:
            value = name.value.decode("utf-8", "replace")
            _x11.XFree(name)
            return value
        return ""

    def size(self, window):
        attributes = _WindowAttributes()
        _x11.XGetWindowAttributes(self.handle, window, ctypes.byref(attributes))
        return attributes.width, attributes.height, attributes.map_state == 2  # IsViewable

    def find(self, title_part):
        """The first viewable top-level window whose title holds `title_part`, or None."""
        for window in self._children(_x11.XDefaultRootWindow(self.handle)):
            if title_part in self.name(window) and self.size(window)[2]:
                return window
        return None

    def resize(self, window, width, height):
        _x11.XMoveResizeWindow(self.handle, window, 0, 0, width, height)
        _x11.XSync(self.handle, 0)

    def drag(self, x0, y0, x1, y1, steps=20, pause=0.02):
        """A left-button drag from (x0, y0) to (x1, y1), screen pixels, as a hand would."""
        import time
        _xtst.XTestFakeMotionEvent(self.handle, -1, x0, y0, 0)
        _xtst.XTestFakeButtonEvent(self.handle, 1, 1, 0)
        _x11.XSync(self.handle, 0)
        for i in range(1, steps + 1):
            time.sleep(pause)
            _xtst.XTestFakeMotionEvent(self.handle, -1, x0 + (x1 - x0) * i // steps,
                                       y0 + (y1 - y0) * i // steps, 0)
            _x11.XSync(self.handle, 0)
        _xtst.XTestFakeButtonEvent(self.handle, 1, 0, 0)
        _x11.XSync(self.handle, 0)

    def capture(self, window):
        """What the server shows in `window`: a (height, width, 3) uint8 array, top row first."""
        import numpy
        width, height, _ = self.size(window)
        pointer = _x11.XGetImage(self.handle, window, 0, 0, width, height, 0xFFFFFFFF, 2)
        if not pointer:
            raise RuntimeError("XGetImage failed")
        image = ctypes.cast(pointer, ctypes.POINTER(_XImage)).contents
        if image.bits_per_pixel != 32:
            raise RuntimeError("expected 32 bits per pixel, got %d" % image.bits_per_pixel)
        raw = numpy.ctypeslib.as_array(image.data, shape=(height * image.bytes_per_line,)).copy()
        image.f_destroy_image(pointer)
        rows = raw.reshape(height, image.bytes_per_line)[:, :4 * width].reshape(height, width, 4)
        return rows[:, :, [2, 1, 0]].copy()  # BGRX (little endian, TrueColor) to RGB


def main(argv):
    display = Display()
    try:
        if argv[0] == "find":
            window = display.find(argv[1])
            if window is None:
                return 1
            print(window)
        elif argv[0] == "list":
            for window in display._children(_x11.XDefaultRootWindow(display.handle)):
                if display.size(window)[2]:
                    print(window, display.size(window), repr(display.name(window)))
        elif argv[0] == "resize":
            display.resize(int(argv[1]), int(argv[2]), int(argv[3]))
        elif argv[0] == "drag":
            display.drag(*[int(a) for a in argv[1:5]])
        elif argv[0] == "capture":
            import numpy
            numpy.save(argv[2], display.capture(int(argv[1])))
        else:
            raise SystemExit(__doc__)
    finally:
        display.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
