//! A 3 x 5 pixel bitmap font for the labels of the pictures (digits,
//! capitals, the punctuation of numbers and units; lower case is drawn as
//! small capitals). Hand-made: no font dependency for a few dozen glyphs.

/// Glyphs as five rows of three cells, `#` lit.
const GLYPHS: &[(char, &str)] = &[
    (' ', "... ... ... ... ..."),
    ('0', "### #.# #.# #.# ###"),
    ('1', ".#. ##. .#. .#. ###"),
    ('2', "### ..# ### #.. ###"),
    ('3', "### ..# .## ..# ###"),
    ('4', "#.# #.# ### ..# ..#"),
    ('5', "### #.. ### ..# ###"),
    ('6', "### #.. ### #.# ###"),
    ('7', "### ..# ..# .#. .#."),
    ('8', "### #.# ### #.# ###"),
    ('9', "### #.# ### ..# ###"),
    ('A', ".#. #.# ### #.# #.#"),
    ('B', "##. #.# ##. #.# ##."),
    ('C', ".## #.. #.. #.. .##"),
    ('D', "##. #.# #.# #.# ##."),
    ('E', "### #.. ##. #.. ###"),
    ('F', "### #.. ##. #.. #.."),
    ('G', ".## #.. #.# #.# .##"),
    ('H', "#.# #.# ### #.# #.#"),
    ('I', "### .#. .#. .#. ###"),
    ('J', "..# ..# ..# #.# .#."),
    ('K', "#.# #.# ##. #.# #.#"),
    ('L', "#.. #.. #.. #.. ###"),
    ('M', "#.# ### ### #.# #.#"),
    ('N', "##. #.# #.# #.# #.#"),
    ('O', ".#. #.# #.# #.# .#."),
    ('P', "##. #.# ##. #.. #.."),
    ('Q', ".#. #.# #.# ##. .##"),
    ('R', "##. #.# ##. #.# #.#"),
    ('S', ".## #.. .#. ..# ##."),
    ('T', "### .#. .#. .#. .#."),
    ('U', "#.# #.# #.# #.# ###"),
    ('V', "#.# #.# #.# #.# .#."),
    ('W', "#.# #.# ### ### #.#"),
    ('X', "#.# #.# .#. #.# #.#"),
    ('Y', "#.# #.# .#. .#. .#."),
    ('Z', "### ..# .#. #.. ###"),
    ('.', "... ... ... ... .#."),
    (',', "... ... ... .#. #.."),
    ('-', "... ... ### ... ..."),
    ('+', "... .#. ### .#. ..."),
    ('/', "..# ..# .#. #.. #.."),
    ('%', "#.# ..# .#. #.. #.#"),
    (':', "... .#. ... .#. ..."),
    ('^', ".#. #.# ... ... ..."),
    ('(', ".#. #.. #.. #.. .#."),
    (')', ".#. ..# ..# ..# .#."),
    ('[', "##. #.. #.. #.. ##."),
    (']', ".## ..# ..# ..# .##"),
    ('_', "... ... ... ... ###"),
    ('=', "... ### ... ### ..."),
    ('<', "..# .#. #.. .#. ..#"),
    ('>', "#.. .#. ..# .#. #.."),
    ('*', "... #.# .#. #.# ..."),
    ('\'', ".#. .#. ... ... ..."),
    ('?', "### ..# .## ... .#."),
];

/// Width and height of a glyph in cells, and the advance to the next one.
pub const GLYPH_WIDTH: usize = 3;
/// Height of a glyph in cells.
pub const GLYPH_HEIGHT: usize = 5;
/// Cells from one glyph's left edge to the next one's.
pub const ADVANCE: usize = 4;

/// Whether cell (`col`, `row`) of `c`'s glyph is lit; characters without a
/// glyph are drawn as `?`.
pub fn lit(c: char, col: usize, row: usize) -> bool {
    let c = c.to_ascii_uppercase();
    let rows = GLYPHS.iter().find(|(g, _)| *g == c).or_else(|| GLYPHS.iter().find(|(g, _)| *g == '?'));
    rows.is_some_and(|(_, rows)| rows.as_bytes().get(row * (GLYPH_WIDTH + 1) + col) == Some(&b'#'))
}

/// Width in cells of a line of text.
pub fn text_width(text: &str) -> usize {
    text.chars().count() * ADVANCE
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_glyph_has_five_rows_of_three() {
        for (c, rows) in GLYPHS {
            let rows: Vec<&str> = rows.split(' ').collect();
            assert_eq!(rows.len(), GLYPH_HEIGHT, "{c}");
            assert!(rows.iter().all(|r| r.len() == GLYPH_WIDTH && r.chars().all(|x| x == '#' || x == '.')), "{c}");
        }
        let distinct: std::collections::HashSet<&str> = GLYPHS.iter().map(|(_, r)| *r).collect();
        assert_eq!(distinct.len(), GLYPHS.len(), "two characters share a glyph");
    }

    #[test]
    fn lower_case_is_small_capitals_and_unknown_is_a_question_mark() {
        assert!(lit('e', 0, 0) && lit('E', 0, 0));
        assert_eq!(
            (0..5).map(|r| lit('~', 1, r)).collect::<Vec<_>>(),
            (0..5).map(|r| lit('?', 1, r)).collect::<Vec<_>>()
        );
        assert!(!lit(' ', 1, 2));
    }
}
