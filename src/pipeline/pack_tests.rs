//! The packs' join policy and their stacked rows.

mod join {
    use super::super::to_join;

    #[test]
    fn the_newest_packs_are_joined_until_the_next_older_holds_as_many() {
        // Nine one-entry packs on a large one: the nine go, not the large.
        assert_eq!(to_join(&[1, 1, 1, 1, 1, 1, 1, 1, 1, 20_000]), 9);
        // A pack of eight then holds as many as the eight newer ones.
        assert_eq!(to_join(&[1, 1, 1, 1, 1, 1, 1, 1, 8, 20_000]), 8);
        assert_eq!(to_join(&[1, 1, 1, 1, 1, 1, 1, 1, 1, 8, 20_000]), 10);
        // Sizes that double with age: the two newest.
        assert_eq!(to_join(&[1, 1, 2, 4, 8, 16, 32, 64, 128]), 2);
        // Packs with no live entry are removed, not a reason to join.
        assert_eq!(to_join(&[1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 20_000]), 9);
        // All of them, when the oldest holds fewer than the rest.
        assert_eq!(to_join(&[5, 5, 5, 5, 5, 5, 5, 5, 5, 30]), 10);
    }
}

mod stack {
    use super::super::{Pending, STACK_EVERY};
    use crate::pipeline::entries::PartEntry;
    use crate::pipeline::keys::Key;
    use crate::table::{Table, TableBuilder};

    /// A part of one row: its index, and a dictionary value of its own.
    fn row(i: usize) -> Table {
        TableBuilder::new()
            .f64_values("x", [i as f64])
            .cat_runs("s", [(Some(format!("file {i}")), 1)])
            .build()
            .unwrap()
    }

    /// Parts stacked as they come (more than one stack's worth, some
    /// parts with no rows of a table) are found at their rows, each with
    /// its own dictionary value.
    #[test]
    fn stacked_parts_are_found_at_their_rows() {
        let n = 2 * STACK_EVERY + 7;
        let mut pending = Pending::default();
        for i in 0..n {
            let mut tables = vec![("t".to_string(), row(i))];
            if i % 3 == 0 {
                tables.push(("u".to_string(), row(i)));
            }
            let entry = PartEntry::Tables(Vec::new());
            pending.put(Key::of_text(&i.to_string()), entry, tables);
        }
        let made = pending.stack().unwrap();
        for i in (0..n).rev() {
            let packed = made.part(&Key::of_text(&i.to_string())).unwrap();
            let t = made.rows(packed, "t").unwrap().slice();
            assert_eq!(t.f64("x").unwrap(), vec![Some(i as f64)]);
            assert_eq!(t.str("s").unwrap(), vec![Some(format!("file {i}"))]);
            let u = made.rows(packed, "u");
            assert_eq!(u.is_ok(), i % 3 == 0, "part {i}");
        }
    }
}
