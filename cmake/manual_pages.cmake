# Man pages and shell completions, generated from the command's own option definitions: the
# built `ibl` walks the CLI11 tree that --help prints (apps/manual.cpp) and writes
#   build/man/man1/ibl.1, build/man/man1/ibl-COMMAND.1   (man -l build/man/man1/ibl-bake.1)
#   build/man/gz/ibl.1.gz, ...                           (installed: compressed, gzip -9n, as
#                                                         Debian's policy asks)
#   build/completions/ibl                                (bash: source build/completions/ibl)
#   build/completions/_ibl                               (zsh)
# Not under the sanitizers (their command is slow to start and not installed).
include(GNUInstallDirs)

if(NOT IBL_SANITIZE AND NOT IBL_TSAN)
  set(IBL_MAN_DIR ${CMAKE_CURRENT_BINARY_DIR}/man/man1)
  set(IBL_COMPLETIONS_DIR ${CMAKE_CURRENT_BINARY_DIR}/completions)
  set(IBL_MAN_GZ_DIR ${CMAKE_CURRENT_BINARY_DIR}/man/gz)
  find_program(IBL_GZIP gzip REQUIRED)
  # One stamp for the command's run: the pages' names follow the commands, which CMake does not
  # know; the folder is emptied first so that a removed command leaves no stale page.
  add_custom_command(
    OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/man/manual.stamp
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${IBL_MAN_DIR} ${IBL_MAN_GZ_DIR}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${IBL_MAN_DIR} ${IBL_MAN_GZ_DIR}
            ${IBL_COMPLETIONS_DIR}
    COMMAND ibl_cli manual --man-dir ${IBL_MAN_DIR} --bash ${IBL_COMPLETIONS_DIR}/ibl
            --zsh ${IBL_COMPLETIONS_DIR}/_ibl
    # -n: no name or time stamp in the header, so that the same page compresses to the same bytes.
    COMMAND sh -c "for page in \"$1\"/*.1; do \"$3\" -9nc \"$page\" > \"$2/\${page##*/}.gz\"; done"
            sh ${IBL_MAN_DIR} ${IBL_MAN_GZ_DIR} ${IBL_GZIP}
    COMMAND ${CMAKE_COMMAND} -E touch ${CMAKE_CURRENT_BINARY_DIR}/man/manual.stamp
    DEPENDS ibl_cli
    BYPRODUCTS ${IBL_COMPLETIONS_DIR}/ibl ${IBL_COMPLETIONS_DIR}/_ibl ${IBL_MAN_DIR}/ibl.1
    COMMENT "man pages and shell completions of ibl"
    VERBATIM)
  add_custom_target(ibl_manual ALL DEPENDS ${CMAKE_CURRENT_BINARY_DIR}/man/manual.stamp)

  if(IBL_INSTALL)
    install(DIRECTORY ${IBL_MAN_GZ_DIR}/ DESTINATION ${CMAKE_INSTALL_MANDIR}/man1
            COMPONENT runtime FILES_MATCHING PATTERN "*.1.gz")
    install(FILES ${IBL_COMPLETIONS_DIR}/ibl
            DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions COMPONENT runtime)
    # zsh reads a system's packages' functions from /usr/share/zsh/vendor-completions (Debian)
    # and a local install's from PREFIX/share/zsh/site-functions: chosen when installing, since
    # cpack installs the same rules under /usr (its staging folder's .../usr).
    install(CODE "
      if(CMAKE_INSTALL_PREFIX MATCHES \"(^|/)usr/?$\")
        set(ibl_zsh_dir vendor-completions)
      else()
        set(ibl_zsh_dir site-functions)
      endif()
      file(INSTALL \"${IBL_COMPLETIONS_DIR}/_ibl\"
           DESTINATION \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/zsh/\${ibl_zsh_dir}\")
    " COMPONENT runtime)
  endif()
endif()
