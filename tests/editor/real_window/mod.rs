//! The real `veneer` binary in a real X window: its own Xvfb display, real key and
//! mouse events through `xdotool`, screenshots through ImageMagick's `import`. The
//! harness is [`session`] (the X server, the editor, input, waits and failures) and
//! [`shot`] (screenshots and what is found in them); each other file is a flow a user
//! goes through. [`first_minute`]: open a copy of a preset, add two nodes by Space +
//! typing + Enter at the mouse, wire them by dragging from an output pin to an input
//! pin, save with Ctrl+S and again with Ctrl+Shift+S + a typed path + Enter, close,
//! reopen the saved file, and compare the files with what was done.
//!
//! Every step waits for something a user would see (a window title, the search popup,
//! each typed letter in it, a node, a wire, a file on disk), polling rather than
//! sleeping (the only pauses pace the mouse as a hand does), and fails after [`session::STEP`]
//! with what it waited for, a screenshot of the screen and one of the window at the end
//! of each earlier step, in `target/e2e-failures/<test>/`. The editor and the X server
//! are each test's own processes, ended by their pids however the test ends.
//!
//! Without Xvfb, xdotool or ImageMagick the test fails (it does not skip), naming the
//! missing tool and `.ci/run`, which installs them.
//!
//! Pins are found on screen rather than computed: a new node is the part of the
//! (empty) canvas that changed when it was added, and its pins are the discs of a pin
//! colour at its left and right edges.

mod canvas;
mod first_minute;
mod gestures;
mod on_disk;
mod panning;
mod probe;
mod selection;
mod session;
mod shot;
