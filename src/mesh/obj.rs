//! The Wavefront OBJ loader: positions (`v`), texture coordinates (`vt`), normals (`vn`)
//! and polygons (`f`, fanned into triangles); points, lines, groups and materials are
//! skipped. A mesh vertex is made for each distinct position/uv/normal triple the faces
//! use, in the order they first use it, and remembers its `v` line, so that distances
//! are given in the file's own numbering.

use super::FileVertices;
use super::load::Soup;
use std::collections::HashMap;

/// Marks a face corner without a texture coordinate or normal.
const NONE: u32 = u32::MAX;

/// What the `v`, `vt`, `vn` and `f` lines of a file hold.
#[derive(Default)]
struct Lists {
    positions: Vec<[f32; 3]>,
    uvs: Vec<[f32; 2]>,
    normals: Vec<[f32; 3]>,
    /// Each triangle's corners as (position, uv, normal) indices, with the line that
    /// gave it.
    corners: Vec<([u32; 3], usize)>,
}

/// The triangles of an OBJ file.
pub(super) fn read(bytes: &[u8]) -> Result<Soup, String> {
    let text = String::from_utf8_lossy(bytes);
    let mut lists = Lists::default();
    let mut pending = String::new();
    let mut first_line = 1;
    for (k, raw) in text.lines().enumerate() {
        if pending.is_empty() {
            first_line = k + 1;
        }
        // A backslash at the end continues the statement on the next line.
        match raw.strip_suffix('\\') {
            Some(head) => {
                pending.push_str(head);
                pending.push(' ');
                continue;
            }
            None => pending.push_str(raw),
        }
        statement(&std::mem::take(&mut pending), first_line, &mut lists)?;
    }
    statement(&pending, first_line, &mut lists)?;
    assemble(lists)
}

/// Reads statement `line` (its first line's number) into `lists`.
fn statement(text: &str, line: usize, lists: &mut Lists) -> Result<(), String> {
    let text = text.split('#').next().unwrap_or_default();
    let mut words = text.split_whitespace();
    match words.next() {
        Some("v") => numbers(words, 3, "v").map(|p| lists.positions.push(p)),
        Some("vt") => numbers(words, 1, "vt").map(|t| lists.uvs.push(t)),
        Some("vn") => numbers(words, 3, "vn").map(|n| lists.normals.push(n)),
        Some("f") => face(words, line, lists),
        _ => Ok(()),
    }
    .map_err(|message| format!("line {line}: {message}"))
}

/// The first `N` numbers of a statement, of which at least `required` must be there
/// (the others are 0).
fn numbers<'a, const N: usize>(
    words: impl Iterator<Item = &'a str>,
    required: usize,
    keyword: &str,
) -> Result<[f32; N], String> {
    let mut values = [0.0; N];
    let mut count = 0;
    for (slot, word) in values.iter_mut().zip(words) {
        *slot = word
            .parse::<f32>()
            .ok()
            .filter(|value| value.is_finite())
            .ok_or_else(|| format!("`{keyword}`: `{word}` is not a finite number"))?;
        count += 1;
    }
    if count < required {
        return Err(format!(
            "`{keyword}` needs {required} numbers, found {count}"
        ));
    }
    Ok(values)
}

/// Reads a polygon's corners (`v`, `v/vt`, `v//vn` or `v/vt/vn`; negative indices count
/// back from the latest) on `line` and fans it into triangles.
fn face<'a>(
    words: impl Iterator<Item = &'a str>,
    line: usize,
    lists: &mut Lists,
) -> Result<(), String> {
    let counts = [lists.positions.len(), lists.uvs.len(), lists.normals.len()];
    let corners = words
        .map(|word| {
            let mut corner = [NONE; 3];
            for (k, part) in word.split('/').enumerate() {
                match (k, part) {
                    (3.., _) => return Err(format!("`{word}` is not a face corner")),
                    (1 | 2, "") => {}
                    _ => corner[k] = index(part, counts[k])?,
                }
            }
            Ok(corner)
        })
        .collect::<Result<Vec<[u32; 3]>, String>>()?;
    if corners.len() < 3 {
        return Err(format!(
            "a face needs at least 3 corners, found {}",
            corners.len()
        ));
    }
    for k in 1..corners.len() - 1 {
        for corner in [corners[0], corners[k], corners[k + 1]] {
            lists.corners.push((corner, line));
        }
    }
    Ok(())
}

/// A 0-based index from OBJ's 1-based (or, when negative, relative to the `count`
/// read so far) one; it is checked against the whole file later.
fn index(text: &str, count: usize) -> Result<u32, String> {
    let value: i64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a vertex index"))?;
    let resolved = match value {
        1.. => value - 1,
        ..0 => count as i64 + value,
        0 => -1,
    };
    u32::try_from(resolved)
        .ok()
        .filter(|&i| i != NONE)
        .ok_or_else(|| format!("index {value} refers to no vertex ({count} read so far)"))
}

/// One mesh vertex per distinct corner, in the order faces first use them.
fn assemble(lists: Lists) -> Result<Soup, String> {
    let mut vertex_of: HashMap<[u32; 3], u32> = HashMap::new();
    let mut soup = Soup {
        positions: Vec::new(),
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        indices: Vec::with_capacity(lists.corners.len()),
        file_vertices: None,
    };
    let mut of_vertex = Vec::new();
    for &(corner, line) in &lists.corners {
        let next = of_vertex.len() as u32;
        let vertex = *vertex_of.entry(corner).or_insert(next);
        if vertex == next {
            let [p, t, n] = corner;
            let beyond = |what: &str, index: u32, count: usize| {
                format!(
                    "line {line}: a face refers to {what} {}, but the file has {count}",
                    u64::from(index) + 1
                )
            };
            let position = lists.positions.get(p as usize);
            soup.positions
                .push(*position.ok_or_else(|| beyond("vertex", p, lists.positions.len()))?);
            of_vertex.push(p);
            attach(&mut soup.uvs, &lists.uvs, t)
                .map_err(|count| beyond("texture coordinate", t, count))?;
            attach(&mut soup.normals, &lists.normals, n)
                .map_err(|count| beyond("normal", n, count))?;
        }
        soup.indices.push(vertex);
    }
    soup.file_vertices = Some(FileVertices {
        of_vertex,
        count: lists.positions.len(),
    });
    Ok(soup)
}

/// Adds `values[index]` to the per-vertex `list`, which is given up (`None`) at the first
/// corner without one ([`NONE`]); `Err` holds the number of values when `index` is past
/// them.
fn attach<T: Copy>(list: &mut Option<Vec<T>>, values: &[T], index: u32) -> Result<(), usize> {
    if index == NONE {
        *list = None;
        return Ok(());
    }
    let value = *values.get(index as usize).ok_or(values.len())?;
    if let Some(list) = list {
        list.push(value);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_become_vertices_in_first_use_order_and_remember_their_v_line() {
        let text = "# a quad over four of five points, the first unused\n\
                    v 9 9 9\nv 0 0 0 1 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 \\\n 0\n\
                    vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n\
                    f 4/3/1 -4//-1 3//1 -1//1\n";
        let soup = read(text.as_bytes()).unwrap();
        assert_eq!(
            soup.indices,
            [0, 1, 2, 0, 2, 3],
            "fanned from the first corner"
        );
        let file = soup.file_vertices.unwrap();
        assert_eq!((file.of_vertex, file.count), (vec![3, 1, 2, 4], 5));
        assert_eq!(soup.positions[3], [0.0, 1.0, 0.0], "continued line");
        assert_eq!(soup.normals.unwrap().len(), 4);
        assert!(
            soup.uvs.is_none(),
            "not every corner has a texture coordinate"
        );
    }

    #[test]
    fn a_vertex_with_two_texture_coordinates_is_split() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\n\
                    f 1/1 2/1 3/1\nf 2/2 4/2 3/2\n";
        let soup = read(text.as_bytes()).unwrap();
        assert_eq!(soup.file_vertices.unwrap().of_vertex, [0, 1, 2, 1, 3, 2]);
        assert_eq!(soup.uvs.unwrap()[3], [1.0, 0.0]);
    }

    #[test]
    fn broken_statements_name_their_line() {
        for (text, message) in [
            ("v 0 0\n", "line 1: `v` needs 3 numbers, found 2"),
            ("v 0 0 inf\n", "line 1: `v`: `inf` is not a finite number"),
            (
                "v 0 0 0\nf 1 1\n",
                "line 2: a face needs at least 3 corners, found 2",
            ),
            (
                "v 0 0 0\nf 0 1 1\n",
                "line 2: index 0 refers to no vertex (1 read so far)",
            ),
            (
                "v 0 0 0\nf 1 -2 1\n",
                "line 2: index -2 refers to no vertex (1 read so far)",
            ),
            (
                "v 0 0 0\nf 1/1/1/1 1 1\n",
                "line 2: `1/1/1/1` is not a face corner",
            ),
            (
                "v 0 0 0\n\nf 1 2 3\n",
                "line 3: a face refers to vertex 2, but the file has 1",
            ),
            (
                "v 0 0 0\nf 1/1 1/1 1/1\n",
                "line 2: a face refers to texture coordinate 1, but the file has 0",
            ),
        ] {
            assert_eq!(
                read(text.as_bytes()).err().as_deref(),
                Some(message),
                "{text}"
            );
        }
    }
}
