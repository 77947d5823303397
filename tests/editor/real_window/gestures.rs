//! What a hand does to the window: keys, typing, moving the mouse, clicks and drags,
//! wiring two pins, adding a node through the search.

use super::session::{STEP, Session};
use super::shot::{Rect, Shot, diff, full, pins};
use std::time::Duration;

/// About a frame or two of the editor's: how long a hand rests between pressing,
/// moving and letting go, so that each reaches the editor in a frame of its own.
const PACE: Duration = Duration::from_millis(150);

/// A node added on screen: where it is, and its first input and output pins.
pub(super) struct Added {
    pub(super) bounds: Rect,
    pub(super) input: Option<(i32, i32)>,
    pub(super) output: Option<(i32, i32)>,
}

/// How the add-node search is opened, the mouse where the node is to go.
#[derive(Clone, Copy)]
pub(super) enum Opener {
    /// The Space key.
    Space,
    /// A right click on empty canvas.
    RightClick,
}

impl Opener {
    /// What the user did, in words.
    fn name(self) -> &'static str {
        match self {
            Opener::Space => "Space",
            Opener::RightClick => "a right click on empty canvas",
        }
    }
}

/// The add-node search, open: where the mouse is, the window before it opened, the
/// columns of the window it may cover, and where it shows.
pub(super) struct Search {
    at: (i32, i32),
    before: Shot,
    columns: Rect,
    popup: Rect,
}

impl Session {
    /// Presses `keys` (an `xdotool key` chord such as `ctrl+s`) in the editor's window.
    pub(super) fn key(&mut self, keys: &str) {
        let window = self.window.clone().expect("a window");
        self.xdotool(&["windowfocus", "--sync", &window]);
        self.xdotool(&["key", keys]);
    }

    /// Types `text` as a typist does, a key every 20 ms.
    pub(super) fn type_text(&mut self, text: &str) {
        self.xdotool(&["type", "--delay", "20", "--", text]);
    }

    /// Moves the pointer to `(x, y)` in the window and waits for it to get there.
    pub(super) fn move_mouse(&mut self, (x, y): (i32, i32)) {
        let window = self.window.clone().expect("a window");
        let (x_text, y_text) = (x.to_string(), y.to_string());
        let mut args = vec!["mousemove", "--window", &window];
        // --sync waits for the pointer to move: not when it is there already.
        if self.mouse != Some((x, y)) {
            args.push("--sync");
        }
        args.extend([x_text.as_str(), y_text.as_str()]);
        self.xdotool(&args);
        self.mouse = Some((x, y));
    }

    /// Drags a wire with the left button from the output pin at `from` (of the node
    /// shown in `node`) to the input pin at `to`, as a hand does, each stage seen on
    /// screen before the next: the pin lit under the pointer, the press (given a frame
    /// of its own: egui finds what was pressed where the pointer is when it reads the
    /// press), a wire following the pointer out of the pin, the wire at the input pin,
    /// the release.
    pub(super) fn drag_wire(&mut self, from: (i32, i32), to: (i32, i32), node: Rect) {
        let before = self.shot();
        self.move_mouse(from);
        self.wait_for("the output pin lit under the pointer", STEP, |s| {
            (diff(&before, &s.shot(), Rect::around(from, 8), false).0 >= 10).then_some(())
        });
        let hovered = self.shot();
        self.xdotool(&["mousedown", "1"]);
        std::thread::sleep(Duration::from_millis(500));
        let length = f64::from((to.0 - from.0).pow(2) + (to.1 - from.1).pow(2))
            .sqrt()
            .max(1.0);
        let along = |distance: f64| {
            (
                from.0 + (f64::from(to.0 - from.0) * distance / length).round() as i32,
                from.1 + (f64::from(to.1 - from.1) * distance / length).round() as i32,
            )
        };
        self.move_mouse(along(16.0));
        let stub = Rect::around(along(11.0), 2);
        let mut rest = node;
        // The node without its pin: what must not move while the wire is drawn out.
        rest.x1 = rest.x1.min(from.0 - 14);
        let pulled = self.wait_for("a wire following the pointer out of the pin", STEP, |s| {
            let now = s.shot();
            if diff(&hovered, &now, rest, false).0 > 100 {
                return Some(false);
            }
            (diff(&hovered, &now, stub, false).0 > 0).then_some(true)
        });
        if !pulled {
            self.xdotool(&["mouseup", "1"]);
            self.fail(
                "pressing the pin and moving away panned the view or moved the node instead \
                 of drawing a wire",
            );
        }
        let steps = 10;
        for i in 1..=steps {
            let distance = 16.0 + (length - 16.0) * f64::from(i) / f64::from(steps);
            self.move_mouse(along(distance));
            // About a frame between moves, as a hand gives.
            std::thread::sleep(Duration::from_millis(30));
        }
        self.move_mouse(to);
        // Wires enter input pins from the left.
        let end = Rect::around((to.0 - 11, to.1), 2);
        self.wait_for("the wire reaching the input pin", STEP, |s| {
            (diff(&hovered, &s.shot(), end, false).0 > 0).then_some(())
        });
        self.xdotool(&["mouseup", "1"]);
    }

    /// Opens the add-node search with the mouse at `at`, by `opener`, and waits for
    /// it to show there.
    pub(super) fn open_search(&mut self, at: (i32, i32), opener: Opener) -> Search {
        self.move_mouse(at);
        let room = Rect::room(at);
        let height = self.shot().height as i32;
        let columns = Rect {
            x0: room.x0,
            y0: 30,
            x1: room.x1,
            y1: height - 30,
        };
        let before = self.settled(columns);
        match opener {
            Opener::Space => self.key("space"),
            Opener::RightClick => self.click(at, "3"),
        }
        // The popup may sit higher than the mouse near the window's bottom edge.
        let what = "the add-node search to open at the mouse";
        let popup = self.try_wait_for(what, STEP, |s| {
            let (count, bounds) = diff(&before, &s.shot(), columns, true);
            bounds.filter(|b| count > 2000 && b.x0 <= at.0 + 5 && b.x1 >= at.0 + 100)
        });
        let Some(popup) = popup else {
            self.fail(&format!(
                "{} opened nothing within {STEP:?}: it opens the add-node search at the mouse",
                opener.name()
            ));
        };
        Search {
            at,
            before,
            columns,
            popup,
        }
    }

    /// Adds a node at `at` as a user does: Space with the mouse there, the query typed
    /// (each key seen in the search before the next), Enter. Returns the node's pins.
    pub(super) fn add_node(&mut self, at: (i32, i32), query: &str) -> Added {
        self.add_node_by(Opener::Space, at, query)
    }

    /// [`Session::add_node`], the search opened by `opener`.
    pub(super) fn add_node_by(&mut self, opener: Opener, at: (i32, i32), query: &str) -> Added {
        let Search {
            at,
            before,
            columns,
            popup,
        } = self.open_search(at, opener);
        let mut last = self.shot();
        for c in query.chars() {
            self.type_text(&c.to_string());
            let typed = format!("'{c}' of '{query}' to show in the search");
            last = self.wait_for(&typed, STEP, |s| {
                let next = s.shot();
                (diff(&last, &next, popup, true).0 > 0).then_some(next)
            });
        }
        self.key("Return");
        let room = Rect::room(at);
        let mut previous: Option<Shot> = None;
        let (bounds, found) = self.wait_for(
            "the new node under the mouse, the search closed",
            STEP,
            |s| {
                let next = s.shot();
                let settled = previous
                    .as_ref()
                    .is_some_and(|p| diff(p, &next, columns, false).0 == 0);
                let (_, bounds) = diff(&before, &next, room, false);
                previous = Some(next.clone());
                let bounds = bounds.filter(|b| settled && b.contains(at))?;
                let found = pins(&next, bounds);
                let middle = (bounds.x0 + bounds.x1) / 2;
                let left = found.iter().any(|p| p.0 < middle);
                let right = found.iter().any(|p| p.0 >= middle);
                (left && right).then_some((bounds, found))
            },
        );
        let middle = (bounds.x0 + bounds.x1) / 2;
        let topmost = |right: bool| {
            found
                .iter()
                .filter(|p| (p.0 >= middle) == right)
                .min_by_key(|p| p.1)
                .copied()
        };
        Added {
            bounds,
            input: topmost(false),
            output: topmost(true),
        }
    }

    /// Adds a node at `at` as a quick typist does: Space, and once the search shows,
    /// the query and Enter at once. Does not wait for the node.
    pub(super) fn add_node_at_once(&mut self, at: (i32, i32), query: &str) {
        self.open_search(at, Opener::Space);
        self.type_text(query);
        self.key("Return");
    }

    /// Zooms the view out by `notches` of the wheel about `at` (the graph's top-left
    /// corner, to make room beside it) and returns the window once it settles.
    pub(super) fn zoom_out(&mut self, at: (i32, i32), notches: u32) -> Shot {
        self.move_mouse(at);
        let repeat = notches.to_string();
        self.xdotool(&["click", "--repeat", &repeat, "--delay", "100", "5"]);
        let whole = full(&self.shot());
        self.settled(whole)
    }

    /// Clicks mouse `button` (1 left, 3 right) at `at` as a hand does: the pointer
    /// there a moment before the press, the button held a moment.
    pub(super) fn click(&mut self, at: (i32, i32), button: &str) {
        self.move_mouse(at);
        std::thread::sleep(PACE);
        self.xdotool(&["mousedown", button]);
        std::thread::sleep(PACE);
        self.xdotool(&["mouseup", button]);
    }

    /// Drags with the left button from `from` to `to` in steps, as a hand does, with
    /// `held` (a key such as `alt`) held down from before the press to after the release.
    pub(super) fn drag(&mut self, from: (i32, i32), to: (i32, i32), held: Option<&str>) {
        self.move_mouse(from);
        if let Some(key) = held {
            self.xdotool(&["keydown", key]);
        }
        std::thread::sleep(PACE);
        self.xdotool(&["mousedown", "1"]);
        std::thread::sleep(PACE);
        let steps = 10;
        for i in 1..=steps {
            self.move_mouse((
                from.0 + (to.0 - from.0) * i / steps,
                from.1 + (to.1 - from.1) * i / steps,
            ));
            std::thread::sleep(Duration::from_millis(30));
        }
        std::thread::sleep(PACE);
        self.xdotool(&["mouseup", "1"]);
        if let Some(key) = held {
            std::thread::sleep(PACE);
            self.xdotool(&["keyup", key]);
        }
    }
}
